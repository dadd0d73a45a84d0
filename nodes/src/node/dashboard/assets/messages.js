// Reads each server message type of docs/dashboard-protocol.md into the plain object the page uses, checking
// every field the page relies on. Unknown fields are ignored; `readMessage` returns null for an
// unknown type (later protocol versions add types).

import { FrameError } from './protocol.js';
import * as f from './fields.js';

function readHello({ header }) {
  const blendObject = f.object(header, 'blend', null);
  const blend = blendObject && f.entry(blendObject, 'hello blend');
  return {
    protocol: f.number(header, 'protocol'),
    namespace: f.optionalString(header, 'namespace'),
    pointBudget: f.optionalNumber(header, 'point_budget'),
    blend: blend && {
      stream: f.string(blend, 'stream'),
      parts: f.stringList(blend, 'parts'),
    },
    arms: f.stringList(header, 'arms'),
    stopBannerAfterMs: f.optionalNumber(header, 'stop_banner_after_ms', 500),
  };
}

function readCloud(frame) {
  const { header } = frame;
  const positions = f.array(frame, 'positions', 'f32', { stride: 3 });
  const count = positions.length / 3;
  const hasIntensity = f.optionalBoolean(header, 'intensity', false);
  const intensity = hasIntensity ? f.array(frame, 'intensity', 'f32') : null;
  if (intensity && intensity.length !== count) {
    throw new FrameError(`cloud: array "intensity" has ${intensity.length} values for ${count} points`);
  }
  const blendSources = f.optionalBoolean(header, 'blend_sources', false);
  if (blendSources && !intensity) throw new FrameError('cloud: "blend_sources" without an intensity array');
  return {
    stream: f.string(header, 'stream'),
    sequence: f.optionalNumber(header, 'sequence'),
    ageMs: f.optionalNumber(header, 'age_ms'),
    pointsTotal: f.optionalNumber(header, 'points_total', count),
    positions,
    intensity,
    blendSources,
  };
}

function readMesh(frame, prefix) {
  const positions = f.array(frame, `${prefix}positions`, 'f32', { stride: 3 });
  const indices = f.array(frame, `${prefix}indices`, 'u32', { stride: 3 });
  f.checkIndices(frame, `${prefix}indices`, indices, positions.length / 3);
  return { positions, indices };
}

function readCertificate(surface) {
  const raw = f.object(surface, 'certificate', null);
  if (!raw) return null;
  const certificate = f.entry(raw, `${surface.type} certificate`);
  const read = (name) => f.optionalNumber(certificate, name);
  return {
    pointsChecked: read('points_checked'), violations: read('violations'),
    minGap: read('min_gap'), meanGap: read('mean_gap'), maxGap: read('max_gap'),
    correctedPoints: read('corrected_points'),
  };
}

function readSurrogate(frame) {
  const { header } = frame;
  const surfaces = f.list(header, 'surfaces').map((raw, index) => {
    const surface = f.entry(raw, `surrogate surfaces[${index}]`);
    const side = f.string(surface, 'side');
    return { side, certificate: readCertificate(surface), mesh: readMesh(frame, `${side}.`) };
  });
  return {
    stream: f.string(header, 'stream'),
    sequence: f.optionalNumber(header, 'sequence'),
    fitMs: f.optionalNumber(header, 'fit_ms'),
    ageMs: f.optionalNumber(header, 'age_ms'),
    direction: f.vector(header, 'direction', 3),
    surfaces,
  };
}

function readSmooth(frame) {
  const { header } = frame;
  return {
    stream: f.string(header, 'stream'),
    kind: f.optionalString(header, 'kind'),
    fitMs: f.optionalNumber(header, 'fit_ms'),
    errorMax: f.optionalNumber(header, 'error_max'),
    errorRmse: f.optionalNumber(header, 'error_rmse'),
    mesh: readMesh(frame, ''),
  };
}

function readArm(frame) {
  const { header } = frame;
  const links = f.stringList(header, 'links');
  const linkOrigins = f.array(frame, 'link_origins', 'f32', { stride: 3, optional: true });
  if (linkOrigins.length !== 0 && linkOrigins.length !== 3 * links.length) {
    throw new FrameError(`arm: "link_origins" has ${linkOrigins.length} values for ${links.length} links`);
  }
  const shapes = (name, stride) => {
    const values = f.array(frame, name, 'f32', { stride, optional: true });
    const owners = f.array(frame, `${name.slice(0, -1)}_links`, 'u32', { optional: true });
    if (owners.length !== values.length / stride) {
      throw new FrameError(`arm: ${values.length / stride} ${name} but ${owners.length} ${name.slice(0, -1)}_links`);
    }
    f.checkIndices(frame, `${name.slice(0, -1)}_links`, owners, links.length);
    return { values, owners };
  };
  return {
    arm: f.string(header, 'arm'),
    links,
    linkOrigins,
    spheres: shapes('spheres', 4),
    capsules: shapes('capsules', 7),
  };
}

const LINK_BANDS = new Set(['stop', 'near', 'clear', 'unobserved']);

function readLinkVerdict(raw, index) {
  const entry = f.entry(raw, `verdict links[${index}]`);
  const band = f.optionalString(entry, 'band', 'unobserved');
  return {
    link: f.string(entry, 'link'),
    clearance: f.optionalNumber(entry, 'clearance'),
    unobserved: f.optionalBoolean(entry, 'unobserved', false),
    band: LINK_BANDS.has(band) ? band : 'unobserved',
  };
}

// The fraction of each joint's velocity limit the verdict allows: in (0, 1] for a clear (required),
// 0 for a stop (absent reads as 0). A clear at 0 or a stop above 0 contradicts itself: refused.
function readSpeedScale(header, stop) {
  if (stop) {
    const scale = f.optionalNumber(header, 'speed_scale', 0);
    if (scale !== 0) throw new FrameError(`verdict: field "speed_scale" is ${scale} with a stop, not 0`);
    return 0;
  }
  const scale = f.number(header, 'speed_scale');
  if (!(scale > 0 && scale <= 1)) throw new FrameError(`verdict: field "speed_scale" is ${scale}, not in (0, 1] for a clear`);
  return scale;
}

function readVerdict({ header }) {
  const verdict = f.string(header, 'verdict');
  // Anything but an explicit clear stops: a verdict the page does not know is not "clear".
  const stop = f.optionalBoolean(header, 'stop', verdict !== 'clear') || verdict !== 'clear';
  const protectiveDistance = f.optionalNumber(header, 'protective_distance');
  if (protectiveDistance !== null && protectiveDistance < 0) {
    throw new FrameError(`verdict: field "protective_distance" is ${protectiveDistance}, not a distance >= 0`);
  }
  return {
    arm: f.string(header, 'arm'),
    verdict,
    stop,
    reason: f.optionalString(header, 'reason'),
    minClearance: f.optionalNumber(header, 'min_clearance'),
    closestLink: f.optionalString(header, 'closest_link'),
    stopDistance: f.optionalNumber(header, 'stop_distance'),
    speedScale: readSpeedScale(header, stop),
    limitingLink: f.optionalString(header, 'limiting_link'),
    protectiveDistance,
    links: f.list(header, 'links').map(readLinkVerdict),
  };
}

function readNodeEntry(raw, index) {
  const entry = f.entry(raw, `nodes nodes[${index}]`);
  return {
    name: f.string(entry, 'name'),
    kind: f.optionalString(entry, 'kind'),
    state: f.optionalString(entry, 'state', 'unknown'),
    pid: f.optionalNumber(entry, 'pid'),
    uptimeS: f.optionalNumber(entry, 'uptime_s'),
    statusAgeS: f.optionalNumber(entry, 'status_age_s'),
    restarts: f.optionalNumber(entry, 'restarts', 0),
    counters: numberMap(entry, 'counters'),
    gauges: numberMap(entry, 'gauges'),
  };
}

// A map of names to numbers; entries that are not finite numbers are left out.
function numberMap(entry, name) {
  const values = f.object(entry, name);
  return Object.fromEntries(Object.entries(values).filter(([, v]) => typeof v === 'number' && Number.isFinite(v)));
}

function readTopic(raw, index) {
  const entry = f.entry(raw, `nodes topics[${index}]`);
  return { topic: f.string(entry, 'topic'), rateHz: f.optionalNumber(entry, 'rate_hz', 0) };
}

function readNodes({ header }) {
  return {
    uptimeS: f.optionalNumber(header, 'uptime_s'),
    nodes: f.list(header, 'nodes').map(readNodeEntry),
    topics: f.list(header, 'topics').map(readTopic),
    dashboard: f.object(header, 'dashboard'),
  };
}

function readBlendResult({ header }) {
  return {
    id: f.number(header, 'id'),
    ok: f.optionalBoolean(header, 'ok', false),
    error: f.optionalString(header, 'error'),
  };
}

function readError({ header }) {
  return { message: f.optionalString(header, 'message', '(no message)') };
}

const READERS = {
  hello: readHello, cloud: readCloud, surrogate: readSurrogate, smooth: readSmooth, arm: readArm,
  verdict: readVerdict, nodes: readNodes, blend_result: readBlendResult, error: readError,
};

// {type, message} for a known type, null for an unknown one; throws FrameError when malformed.
export function readMessage(frame) {
  const reader = READERS[frame.header.type];
  return reader ? { type: frame.header.type, message: reader(frame) } : null;
}
