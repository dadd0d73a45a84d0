// Turns messages into plot samples: fit time and latency (p50, p99) from the fit nodes' gauges,
// message rates from `topics`, drops per second from the nodes' `dropped_*` counters (all of
// `nodes`), and clearance per link from verdicts.

const GAUGE_PLOTS = [
  ['fit', 'fit_p50_ms', 'p50'], ['fit', 'fit_p99_ms', 'p99'],
  ['latency', 'latency_p50_ms', 'p50'], ['latency', 'latency_p99_ms', 'p99'],
];
const CLEARANCE_SAMPLE_MS = 100; // verdicts come at the joint rate; the plot needs far fewer

export class PlotFeeds {
  // `plots`: {fit, latency, clearance, rates, drops} TimeSeriesPlots.
  constructor(plots) {
    this.plots = plots;
    this.previousDrops = null; // {tMs, byNode: Map(name -> total)}
    this.lastClearanceMs = new Map(); // arm -> time of its last sample
  }

  onNodes(message, tMs) {
    for (const node of message.nodes) {
      for (const [plot, gauge, label] of GAUGE_PLOTS) {
        if (gauge in node.gauges) this.plots[plot].push(`${node.name} ${label}`, tMs, node.gauges[gauge]);
      }
    }
    for (const topic of message.topics) this.plots.rates.push(topic.topic, tMs, topic.rateHz);
    this.pushDropRate(message.nodes, tMs);
  }

  // Drops per second since the previous `nodes`. A counter that went down belongs to a restarted
  // node: its whole new value is dropped since the restart.
  pushDropRate(nodes, tMs) {
    const byNode = new Map(nodes.map((node) => [node.name, droppedTotal(node.counters)]));
    const previous = this.previousDrops;
    this.previousDrops = { tMs, byNode };
    if (!previous || tMs <= previous.tMs) return;
    let dropped = 0;
    for (const [name, total] of byNode) {
      const before = previous.byNode.get(name) ?? 0;
      dropped += total >= before ? total - before : total;
    }
    this.plots.drops.push('all nodes', tMs, (dropped * 1000) / (tMs - previous.tMs));
  }

  onVerdict(verdict, tMs) {
    if (tMs - (this.lastClearanceMs.get(verdict.arm) ?? -Infinity) < CLEARANCE_SAMPLE_MS) return;
    this.lastClearanceMs.set(verdict.arm, tMs);
    for (const link of verdict.links) {
      if (link.clearance !== null) this.plots.clearance.push(`${verdict.arm}/${link.link}`, tMs, link.clearance);
    }
    if (verdict.stopDistance !== null) this.plots.clearance.setReference(verdict.stopDistance, 'stop distance');
  }
}

function droppedTotal(counters) {
  let total = 0;
  for (const [name, value] of Object.entries(counters)) if (name.startsWith('dropped_')) total += value;
  return total;
}
