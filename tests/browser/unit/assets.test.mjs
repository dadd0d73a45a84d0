// The page's files hang together: every module an asset imports exists, every asset is reachable
// from index.html, and the file list in docs/dashboard-protocol.md (the files the node embeds) is exactly the files
// of assets/. Run: node --test tests/browser/unit/

import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { test } from 'node:test';
import { fileURLToPath } from 'node:url';

const DASHBOARD = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../nodes/src/node/dashboard');
const ASSETS = path.join(DASHBOARD, 'assets');

function assetFiles(dir = ASSETS) {
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((entry) => {
    const full = path.join(dir, entry.name);
    return entry.isDirectory() ? assetFiles(full) : [path.relative(ASSETS, full).split(path.sep).join('/')];
  });
}

// The relative URLs a file loads: module imports, and src/href attributes in HTML.
function references(file) {
  const text = fs.readFileSync(path.join(ASSETS, file), 'utf8');
  const pattern = file.endsWith('.html') ? /(?:src|href)="(\.?\/?[\w/.-]+\.(?:js|css))"/g : /^import[^'"]*from '(\.[^']+)';$/gm;
  return [...text.matchAll(pattern)].map((match) => path.posix.normalize(path.posix.join(path.posix.dirname(file), match[1])));
}

test('every import and link of the page names an asset, and every asset is reached from index.html', () => {
  const files = new Set(assetFiles());
  const reached = new Set(['index.html']);
  const queue = ['index.html'];
  while (queue.length > 0) {
    const file = queue.pop();
    for (const target of references(file)) {
      assert.ok(files.has(target), `${file} loads ${target}, which is not in assets/`);
      if (!reached.has(target)) {
        reached.add(target);
        queue.push(target);
      }
    }
  }
  assert.deepEqual([...files].filter((file) => !reached.has(file)), [], 'assets nothing loads');
});

test('docs/dashboard-protocol.md lists exactly the files of assets/', () => {
  const protocol = fs.readFileSync(path.join(DASHBOARD, '../../../../docs/dashboard-protocol.md'), 'utf8');
  const section = protocol.split('## Serving the page')[1];
  const listed = section.split('```')[1].split(/\s+/).filter(Boolean).sort();
  assert.deepEqual(listed, assetFiles().sort());
});
