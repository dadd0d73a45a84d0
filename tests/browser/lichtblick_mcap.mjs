// Reads an MCAP recording the way Lichtblick opens a local file (its
// McapIndexedIterableSource and packages/mcap-support parseChannel, main
// branch as of December 2026): @mcap/core's indexed reader with zstd from
// @lichtblick/wasm-zstd; a channel is decoded by its encodings (protobuf from
// the schema's FileDescriptorSet with protobufjs, JSON with a jsonschema
// schema) or listed as a problem, as the app lists it. Prints a JSON summary
// for tests/record_replay.rs.
//
// usage: node lichtblick_mcap.mjs FILE

import { McapIndexedReader } from "@mcap/core";
import * as zstd from "@lichtblick/wasm-zstd";
import protobufjs from "protobufjs";
import descriptor from "protobufjs/ext/descriptor/index.js";
import { open } from "node:fs/promises";

const [file] = process.argv.slice(2);
const handle = await open(file, "r");
const readable = {
  size: async () => BigInt((await handle.stat()).size),
  read: async (offset, size) => {
    const buffer = new Uint8Array(Number(size));
    await handle.read(buffer, 0, Number(size), Number(offset));
    return buffer;
  },
};
await zstd.isLoaded;
const reader = await McapIndexedReader.Initialize({
  readable,
  decompressHandlers: { zstd: (data, size) => zstd.decompress(data, Number(size)) },
});

// A decoder per channel, or the problem the app would list.
function parseChannel(channel) {
  const schema = reader.schemasById.get(channel.schemaId);
  if (channel.messageEncoding === "json") {
    if (schema && schema.encoding !== "jsonschema") {
      throw new Error(`json with schema encoding ${schema.encoding}`);
    }
    if (schema && typeof JSON.parse(new TextDecoder().decode(schema.data)) !== "object") {
      throw new Error("a JSON schema that is not an object");
    }
    return (data) => JSON.parse(new TextDecoder().decode(data));
  }
  if (channel.messageEncoding === "protobuf") {
    if (schema?.encoding !== "protobuf") {
      throw new Error(`protobuf with schema encoding ${schema?.encoding}`);
    }
    const set = descriptor.FileDescriptorSet.decode(schema.data);
    const root = protobufjs.Root.fromDescriptor(set);
    root.resolveAll();
    const type = root.lookupType(schema.name);
    return (data) => type.toObject(type.decode(data), { defaults: true, longs: Number });
  }
  throw new Error(`Unsupported encoding ${channel.messageEncoding}`);
}

const decoders = new Map();
const problems = [];
const topics = {};
for (const channel of reader.channelsById.values()) {
  try {
    decoders.set(channel.id, parseChannel(channel));
    const schema = reader.schemasById.get(channel.schemaId);
    topics[channel.topic] = {
      schema: schema?.name ?? "",
      count: Number(reader.statistics?.channelMessageCounts.get(channel.id) ?? 0),
      decoded: 0,
    };
  } catch (error) {
    problems.push({ topic: channel.topic, message: String(error.message) });
  }
}

const first = {};
const names = Object.keys(topics);
for await (const message of reader.readMessages({ topics: names, validateCrcs: true })) {
  const channel = reader.channelsById.get(message.channelId);
  const value = decoders.get(message.channelId)(message.data);
  topics[channel.topic].decoded += 1;
  first[channel.topic] ??= summarize(value);
}

// What the test looks at in one decoded message (field names as the
// descriptor gives them, snake_case, as Lichtblick's panels see them).
function summarize(value) {
  if (value.point_stride !== undefined) {
    return {
      frame_id: value.frame_id,
      point_stride: value.point_stride,
      fields: value.fields.map((f) => f.name),
      points: value.data.length / value.point_stride,
    };
  }
  if (value.entities !== undefined) {
    return {
      entities: value.entities.map((e) => ({
        id: e.id,
        frame_id: e.frame_id,
        triangles: e.triangles.reduce(
          (n, t) => n + (t.indices.length > 0 ? t.indices.length : t.points.length) / 3,
          0,
        ),
      })),
    };
  }
  return value;
}

console.log(JSON.stringify({ problems, topics, first }));
await handle.close();
