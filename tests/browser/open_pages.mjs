// Keeps N dashboard pages open in one headless Chromium until stdin closes or SIGTERM: the
// browsers of `shroud-bench consumers --browsers`. Prints "open N" on stdout once every page
// has its hello, then, at exit, one JSON line on stderr with the frames each page counted.
//
//   node tests/browser/open_pages.mjs --url http://127.0.0.1:8080 --count 3

import { MissingTool, openPage } from './lib/browser.mjs';

const EXIT = { ok: 0, failed: 1, usage: 2, missingTool: 3 };

function option(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  return i >= 0 && i + 1 < process.argv.length ? process.argv[i + 1] : fallback;
}

async function main() {
  const url = option('url');
  const count = Number(option('count', '1'));
  const chromium = option('chromium', process.env.SHROUD_CHROMIUM || '/usr/bin/chromium');
  if (!url || !Number.isInteger(count) || count < 1 || count > 16) {
    process.stderr.write('usage: node open_pages.mjs --url URL --count N (1..16) [--chromium PATH]\n');
    process.exit(EXIT.usage);
  }
  const first = await openPage({ url, chromium, viewport: { width: 1280, height: 800 } });
  const pages = [first.page];
  for (let i = 1; i < count; i += 1) {
    const page = await first.browser.newPage({ viewport: { width: 1280, height: 800 } });
    await page.goto(url);
    pages.push(page);
  }
  for (const page of pages) {
    await page.waitForFunction(() => document.body.dataset.hello === 'received', null, { timeout: 30000 });
  }
  process.stdout.write(`open ${count}\n`);
  const finish = async () => {
    const frames = [];
    for (const page of pages) {
      frames.push(await page.evaluate(() => document.getElementById('frames')?.textContent ?? '').catch(() => ''));
    }
    process.stderr.write(`${JSON.stringify({ pages: count, frames, problems: first.problems })}\n`);
    await first.browser.close();
    process.exit(EXIT.ok);
  };
  process.on('SIGTERM', finish);
  process.stdin.on('end', finish);
  process.stdin.resume();
}

main().catch((error) => {
  process.stderr.write(`open_pages: ${error.message}\n`);
  process.exit(error instanceof MissingTool ? EXIT.missingTool : EXIT.failed);
});
