// The latest verdict of each arm with the page's own receipt time, and which arms the page must
// hear from: those the hello names and any arm a verdict names. A verdict is fresh for
// `stop_banner_after_ms` (from the hello) after it arrived; after that the arm counts as unheard.

export class VerdictBook {
  constructor() {
    this.latest = new Map(); // arm -> {verdict, receivedMs}
    this.announcedArms = [];
    this.freshForMs = 500;
  }

  onHello(hello) {
    this.announcedArms = hello.arms;
    this.freshForMs = hello.stopBannerAfterMs;
  }

  record(verdict, nowMs) {
    this.latest.set(verdict.arm, { verdict, receivedMs: nowMs });
  }

  arms() {
    return [...new Set([...this.announcedArms, ...this.latest.keys()])];
  }

  // {verdict, ageMs} of the arm's latest verdict, or null before its first.
  last(arm, nowMs) {
    const entry = this.latest.get(arm);
    return entry ? { verdict: entry.verdict, ageMs: nowMs - entry.receivedMs } : null;
  }

  fresh(arm, nowMs) {
    const last = this.last(arm, nowMs);
    return last && last.ageMs <= this.freshForMs ? last.verdict : null;
  }
}
