// plots: the plots advance. Reads each plot's last sample time (data-last-sample-ms), then waits
// until every plot named by --plots has a later sample.

import { CheckFailed, waitForHello, waitInPage } from '../lib/page.mjs';

const KNOWN = ['fit', 'latency', 'clearance', 'rates', 'drops'];

const readPlots = (page) => page.evaluate((names) => Object.fromEntries(names.map((name) => {
  const canvas = document.getElementById(`plot-${name}`);
  const last = canvas.dataset.lastSampleMs;
  return [name, { last_sample_ms: last === undefined ? null : Number(last), samples: Number(canvas.dataset.samples || 0) }];
})), KNOWN);

export async function run({ page, options, timeoutMs }) {
  const required = options.plots.split(',').map((name) => name.trim()).filter(Boolean);
  const unknown = required.filter((name) => !KNOWN.includes(name));
  if (unknown.length > 0) throw new CheckFailed(`--plots names unknown plots ${unknown.join(', ')} (known: ${KNOWN.join(', ')})`);
  await waitForHello(page, timeoutMs);
  await waitInPage(page, `a first sample in plots ${required.join(', ')}`, (names) =>
    names.every((name) => document.getElementById(`plot-${name}`).dataset.lastSampleMs !== undefined), required, timeoutMs);
  const first = await readPlots(page);
  await waitInPage(page, `a later sample in plots ${required.join(', ')}`, ([names, before]) =>
    names.every((name) => Number(document.getElementById(`plot-${name}`).dataset.lastSampleMs) > before[name].last_sample_ms),
  [required, first], timeoutMs);
  const second = await readPlots(page);
  const advanced = KNOWN.filter((name) => first[name].last_sample_ms !== null &&
    second[name].last_sample_ms > first[name].last_sample_ms);
  return { required, advanced, first, second };
}
