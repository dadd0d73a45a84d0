// The STOP banner: shows STOP with its reason for every arm whose latest verdict stops, whose
// verdicts fell silent for longer than stop_banner_after_ms ("no-verdict"), and for every arm
// while the socket is closed: silence is never clear. A slim CLEAR bar otherwise.

const formatMetres = (value) => (value === null ? 'unknown' : `${value.toFixed(3)} m`);

// {state: "stop" | "clear" | "none", lines: [text]} for the arms in `book` at `nowMs`.
export function bannerState({ socketOpen, helloReceived, book, nowMs }) {
  if (!socketOpen) {
    return { state: 'stop', lines: ['disconnected: the dashboard\'s socket is closed, no verdict can arrive'] };
  }
  if (!helloReceived) return { state: 'stop', lines: ['no-verdict: waiting for the node\'s hello'] };
  const arms = book.arms();
  if (arms.length === 0) return { state: 'none', lines: ['no arm: the node reports no arm to guard'] };
  const stops = [];
  const clears = [];
  for (const arm of arms) {
    const last = book.last(arm, nowMs);
    if (!last) {
      stops.push(`${arm} — no-verdict: the dashboard hears no guard (none yet)`);
    } else if (last.ageMs > book.freshForMs) {
      stops.push(`${arm} — no-verdict: the dashboard hears no guard (last verdict ${(last.ageMs / 1000).toFixed(1)} s ago)`);
    } else if (last.verdict.stop) {
      stops.push(`${arm} — ${last.verdict.verdict}: ${last.verdict.reason || '(no reason given)'}`);
    } else {
      const link = last.verdict.closestLink ? ` (${last.verdict.closestLink})` : '';
      clears.push(`${arm} — clear, clearance ${formatMetres(last.verdict.minClearance)}${link}`);
    }
  }
  return stops.length > 0 ? { state: 'stop', lines: stops } : { state: 'clear', lines: clears };
}

export class StopBanner {
  constructor(element) {
    this.element = element;
    this.rendered = '';
  }

  show({ state, lines }) {
    const key = state + lines.join('\n');
    if (key === this.rendered) return;
    this.rendered = key;
    this.element.dataset.state = state;
    const title = document.createElement('strong');
    title.textContent = state === 'stop' ? 'STOP' : state === 'clear' ? 'CLEAR' : 'NO ARM';
    const reasons = document.createElement('div');
    reasons.className = 'banner-lines';
    for (const line of lines) {
      const row = document.createElement('div');
      row.textContent = line;
      reasons.append(row);
    }
    this.element.replaceChildren(title, reasons);
  }
}
