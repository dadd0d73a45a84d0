// Headless Chromium for the checks: launched from the system package (playwright-core downloads
// no browser), with every console error or warning, uncaught page error and failed request
// recorded as a problem the checks report.

import fs from 'node:fs';

export class MissingTool extends Error {}
export class PageUnreachable extends Error {}

// --use-angle=swiftshader rather than --disable-gpu: with --disable-gpu the software compositor
// reads every WebGL frame back and Chromium logs each read as a console warning ("GPU stall due
// to ReadPixels"), which would drown the page's own warnings. SwiftShader still gives WebGL2.
const CHROMIUM_ARGS = [
  '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
  '--disable-quic',
];

async function loadPlaywright() {
  try {
    return await import('playwright-core');
  } catch (error) {
    throw new MissingTool(`playwright-core is not installed (${error.message}): run npm ci --prefix tests/browser`);
  }
}

// Opens `url` in a fresh browser; returns {browser, page, problems}.
export async function openPage({ url, chromium: executablePath, viewport }) {
  if (!fs.existsSync(executablePath)) {
    throw new MissingTool(`Chromium not found at ${executablePath}: apt-get install chromium (or pass --chromium PATH)`);
  }
  const { chromium } = await loadPlaywright();
  const browser = await chromium.launch({ executablePath, args: CHROMIUM_ARGS });
  const page = await browser.newPage({ viewport });
  const problems = [];
  page.on('console', (message) => {
    if (message.type() === 'error' || message.type() === 'warning') {
      problems.push(`console ${message.type()}: ${message.text()}`);
    }
  });
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()} (${request.failure()?.errorText})`));
  page.on('response', (response) => {
    if (response.status() >= 400) problems.push(`HTTP ${response.status()} for ${response.url()}`);
  });
  try {
    await page.goto(url);
  } catch (error) {
    await browser.close();
    throw new PageUnreachable(`cannot open ${url}: ${error.message.split('\n')[0].replace(/\x1b\[[0-9;]*m/g, '')}`);
  }
  return { browser, page, problems };
}
