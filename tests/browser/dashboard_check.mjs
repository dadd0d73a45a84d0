// Runs one check of the dashboard page in headless Chromium and prints its result as one JSON
// line on stdout: {"check", "ok", ...details} or {"check", "ok": false, "error"}. A screenshot of
// the page goes to --out/<check>.png either way. Exit status: 0 passed, 1 failed, 2 usage error,
// 3 a tool is missing (Chromium or playwright-core). Driven by tests/dashboard.rs.
//
//   node tests/browser/dashboard_check.mjs --url http://127.0.0.1:8080 --out DIR --check loads

import fs from 'node:fs';
import path from 'node:path';
import { CHECKS } from './checks/index.mjs';
import { UsageError, parseArgs, usage } from './lib/args.mjs';
import { MissingTool, PageUnreachable, openPage } from './lib/browser.mjs';
import { CheckFailed } from './lib/page.mjs';

const EXIT = { passed: 0, failed: 1, usage: 2, missingTool: 3 };
// The README's screenshot is larger; the checks draw less (software rendering on two cores).
const VIEWPORT = { width: 1280, height: 800 };
const SCREENSHOT_VIEWPORT = { width: 1600, height: 1000 };

function report(result, exitCode) {
  process.stdout.write(`${JSON.stringify(result)}\n`);
  if (!result.ok) process.stderr.write(`dashboard check ${result.check} failed: ${result.error}\n`);
  process.exit(exitCode);
}

async function main() {
  let options;
  try {
    options = parseArgs(process.argv.slice(2));
    if (!CHECKS[options.check]) throw new UsageError(`unknown check "${options.check}"`);
  } catch (error) {
    if (!(error instanceof UsageError)) throw error;
    process.stderr.write(`${error.message}\n${usage(Object.keys(CHECKS))}\n`);
    process.exit(EXIT.usage);
  }
  const check = options.check;
  const out = path.resolve(options.out);
  fs.mkdirSync(out, { recursive: true });
  let session = null;
  let result;
  let exitCode;
  try {
    const viewport = check === 'screenshot' ? SCREENSHOT_VIEWPORT : VIEWPORT;
    session = await openPage({ url: options.url, chromium: options.chromium, viewport });
    const details = await CHECKS[check]({ ...session, options, out, timeoutMs: options['timeout-ms'] });
    const screenshot = await saveScreenshot(session.page, out, check);
    result = { check, ok: true, ...details, screenshot, problems: session.problems };
    exitCode = EXIT.passed;
  } catch (error) {
    const screenshot = session ? await saveScreenshot(session.page, out, check) : null;
    const expected = [CheckFailed, MissingTool, PageUnreachable].some((kind) => error instanceof kind);
    const message = expected ? error.message : `${error.name}: ${error.message}`;
    result = { check, ok: false, error: message, screenshot, problems: session?.problems ?? [] };
    exitCode = error instanceof MissingTool ? EXIT.missingTool : EXIT.failed;
  } finally {
    await session?.browser.close();
  }
  report(result, exitCode);
}

async function saveScreenshot(page, out, check) {
  const file = path.join(out, `${check}.png`);
  try {
    await page.screenshot({ path: file, fullPage: true });
    return file;
  } catch {
    return null; // the page is gone (the browser crashed): the result says why
  }
}

main();
