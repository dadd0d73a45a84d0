// Command-line options of dashboard_check.mjs: `--name value` pairs, checked and typed here so a
// mistake in the calling test is a clear usage error, not a confusing browser failure.

export class UsageError extends Error {}

const OPTIONS = {
  url: { required: true, help: 'the dashboard page, e.g. http://127.0.0.1:8080' },
  out: { required: true, help: 'directory for screenshots (created)' },
  check: { required: true, help: 'the check to run' },
  node: { help: 'node_dies: the node whose row must turn red' },
  'killed-at-ms': { number: true, help: 'node_dies: when the node was killed (ms since the Unix epoch); without it the check waits for the row to be alive, prints "ready" on stderr and reads that time from stdin' },
  expect: { help: 'stop_banner, speed_gauge: text the banner, or the gauge\'s row, must contain' },
  plots: { default: 'rates,drops', help: 'plots: the plots that must advance (fit, latency, clearance, rates, drops)' },
  'timeout-ms': { number: true, default: 30000, help: 'how long any one wait may take' },
  chromium: { default: process.env.SHROUD_CHROMIUM || '/usr/bin/chromium', help: 'the Chromium binary' },
};

export function usage(checkNames) {
  const lines = Object.entries(OPTIONS).map(([name, o]) => `  --${name}${o.required ? '' : ' (optional)'}: ${o.help}`);
  return `usage: node dashboard_check.mjs --url URL --out DIR --check NAME [options]\n` +
    `checks: ${checkNames.join(', ')}\n${lines.join('\n')}`;
}

export function parseArgs(argv) {
  const values = {};
  for (let i = 0; i < argv.length; i += 2) {
    const name = argv[i].replace(/^--/, '');
    const option = OPTIONS[name];
    if (!argv[i].startsWith('--') || !option) throw new UsageError(`unknown option ${argv[i]}`);
    if (i + 1 >= argv.length) throw new UsageError(`--${name} needs a value`);
    const raw = argv[i + 1];
    if (option.number && !Number.isFinite(Number(raw))) throw new UsageError(`--${name} ${raw}: not a number`);
    values[name] = option.number ? Number(raw) : raw;
  }
  for (const [name, option] of Object.entries(OPTIONS)) {
    if (values[name] === undefined && option.default !== undefined) values[name] = option.default;
    if (values[name] === undefined && option.required) throw new UsageError(`--${name} is required`);
  }
  return values;
}
