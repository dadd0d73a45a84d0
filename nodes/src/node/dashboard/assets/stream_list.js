// The list of clouds under the toolbar: per stream, the points this browser gets out of the
// cloud's total (the node decimates to the point budget), the cloud's age when the node received it
// (its pipeline time) and how long ago the page received it.

import { count, fixed } from './format.js';

export class StreamList {
  constructor(element) {
    this.element = element;
    this.latest = new Map(); // stream -> {cloud, receivedMs}
  }

  onCloud(cloud, nowMs) {
    this.latest.set(cloud.stream, { cloud, receivedMs: nowMs });
  }

  render(nowMs) {
    const rows = [...this.latest].map(([stream, { cloud, receivedMs }]) => {
      const row = document.createElement('div');
      row.dataset.stream = stream;
      const name = document.createElement('b');
      name.textContent = stream;
      const sent = cloud.positions.length / 3;
      const decimated = cloud.pointsTotal > sent ? ` of ${count(cloud.pointsTotal)}` : '';
      const age = cloud.ageMs === null ? '' : `, ${fixed(cloud.ageMs, 1)} ms old at the node`;
      row.append(name, ` ${count(sent)}${decimated} points${age}, received ${fixed((nowMs - receivedMs) / 1000, 1)} s ago`);
      return row;
    });
    this.element.replaceChildren(...rows);
    this.element.hidden = rows.length === 0;
  }
}
