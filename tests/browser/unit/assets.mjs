// Loads the dashboard page's ES modules (nodes/src/node/dashboard/assets) into Node for unit tests:
// the assets have no package.json (they are served as-is), so they are copied beside one that
// marks them as ES modules.

import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const ASSETS = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../../nodes/src/node/dashboard/assets');

let copy = null;

export async function importAsset(name) {
  if (copy === null) {
    copy = fs.mkdtempSync(path.join(os.tmpdir(), 'shroud-assets-'));
    fs.cpSync(ASSETS, copy, { recursive: true });
    fs.writeFileSync(path.join(copy, 'package.json'), '{"type": "module"}\n');
    process.on('exit', () => fs.rmSync(copy, { recursive: true, force: true }));
  }
  return import(pathToFileURL(path.join(copy, name)).href);
}
