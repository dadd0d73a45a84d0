// The speed gauge beside the STOP banner: for each arm, the fraction of each joint's velocity limit
// its guard's latest verdict allows (speed and separation monitoring), as a bar from 0 to 100 %
// with the link that limits it and that link's protective separation distance S_p. Only a fresh
// clear moves the arm: a stop, a verdict older than stop_banner_after_ms, no verdict yet and a
// closed socket all show "stopped" at 0 %, as the banner shows STOP.

// The scale in whole percent, rounded down (0.29 is 29 %, not the 28.999... of 100 * 0.29) so that
// a slowed arm never reads 100 %; "<1 %" for a moving arm below 1 %.
export function percent(scale) {
  if (scale > 0 && scale < 0.01) return '<1 %';
  return `${Math.min(Math.floor(100 * scale + 1e-9), scale < 1 ? 99 : 100)} %`;
}

// One arm's gauge row: {arm, state: "full" | "scaled" | "stopped", scale, text, detail}.
function armRow(arm, last, freshForMs) {
  const stopped = (why) => ({ arm, state: 'stopped', scale: 0, text: 'stopped', detail: why });
  if (!last) return stopped('no verdict yet');
  if (last.ageMs > freshForMs) return stopped(`no verdict for ${(last.ageMs / 1000).toFixed(1)} s`);
  const { verdict } = last;
  if (verdict.stop) return stopped(`verdict ${verdict.verdict}`);
  const scale = verdict.speedScale;
  if (scale >= 1) return { arm, state: 'full', scale: 1, text: 'full speed', detail: 'no link limits it' };
  const sp = verdict.protectiveDistance === null ? '' : ` (S_p ${verdict.protectiveDistance.toFixed(3)} m)`;
  const detail = verdict.limitingLink ? `limited by ${verdict.limitingLink}${sp}` : 'rise-limited (speeding up)';
  return { arm, state: 'scaled', scale, text: `${percent(scale)} speed`, detail };
}

// {state: "stopped" | "none" | "rows", rows: [row]} for the arms in `book` at `nowMs`.
export function speedGaugeState({ socketOpen, helloReceived, book, nowMs }) {
  if (!socketOpen) return { state: 'stopped', rows: [{ arm: '', state: 'stopped', scale: 0, text: 'stopped', detail: 'disconnected' }] };
  if (!helloReceived) return { state: 'stopped', rows: [{ arm: '', state: 'stopped', scale: 0, text: 'stopped', detail: 'no hello yet' }] };
  const arms = book.arms();
  if (arms.length === 0) return { state: 'none', rows: [] };
  return { state: 'rows', rows: arms.map((arm) => armRow(arm, book.last(arm, nowMs), book.freshForMs)) };
}

export class SpeedGauge {
  constructor(element) {
    this.element = element;
    this.rendered = '';
  }

  show({ state, rows }) {
    const key = JSON.stringify([state, rows]);
    if (key === this.rendered) return;
    this.rendered = key;
    this.element.dataset.state = state;
    const title = document.createElement('div');
    title.className = 'gauge-title';
    title.textContent = 'Speed';
    title.title = "the fraction of each joint's velocity limit the guard's latest verdict allows";
    const list = document.createElement('div');
    list.className = 'gauge-rows';
    if (state === 'none') {
      const none = document.createElement('div');
      none.className = 'gauge-detail';
      none.textContent = 'no arm: the node reports no arm to guard';
      list.append(none);
    } else {
      list.append(...rows.map((row) => this.renderRow(row, rows.length > 1)));
    }
    this.element.replaceChildren(title, list);
  }

  renderRow(row, named) {
    const line = document.createElement('div');
    line.className = 'gauge-row';
    line.dataset.state = row.state;
    line.dataset.arm = row.arm;
    line.dataset.scale = String(row.scale);
    const bar = document.createElement('div');
    bar.className = 'gauge-bar';
    bar.setAttribute('role', 'meter');
    bar.setAttribute('aria-valuemin', '0');
    bar.setAttribute('aria-valuemax', '100');
    bar.setAttribute('aria-valuenow', String(100 * row.scale));
    bar.setAttribute('aria-label', `${row.arm || 'arm'} speed`);
    const fill = document.createElement('div');
    fill.className = 'gauge-fill';
    fill.style.width = `${(100 * row.scale).toFixed(1)}%`;
    const ticks = document.createElement('div');
    ticks.className = 'gauge-ticks';
    for (const tick of ['0', '50', '100 %']) {
      const label = document.createElement('span');
      label.textContent = tick;
      ticks.append(label);
    }
    bar.append(fill);
    const text = document.createElement('div');
    text.className = 'gauge-text';
    const value = document.createElement('strong');
    value.textContent = named ? `${row.arm}: ${row.text}` : row.text;
    const detail = document.createElement('span');
    detail.className = 'gauge-detail';
    detail.textContent = row.detail;
    detail.title = row.detail;
    text.append(value, detail);
    const meter = document.createElement('div');
    meter.className = 'gauge-meter';
    meter.append(bar, ticks);
    line.append(meter, text);
    return line;
  }
}
