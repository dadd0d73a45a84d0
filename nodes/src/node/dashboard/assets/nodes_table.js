// The Nodes panel: one entry per node of the latest `nodes` message (state, pid, uptime,
// restarts, status age, then its counters on a second line). Nodes whose state is gone or silent
// are painted red; the whole table dims while the socket is closed (its contents are old).

import { DASH, cell, count, duration } from './format.js';

const DOWN_STATES = new Set(['gone', 'silent']);

export class NodesTable {
  constructor(table, summary) {
    this.table = table;
    this.summary = summary;
  }

  update(message) {
    const bodies = message.nodes.map((node) => nodeBody(node));
    this.table.querySelectorAll('tbody').forEach((body) => body.remove());
    this.table.append(...bodies);
    const down = message.nodes.filter((node) => DOWN_STATES.has(node.state)).length;
    this.summary.textContent = `${message.nodes.length} nodes, ${down} down`;
    this.summary.classList.toggle('bad', down > 0);
  }

  setConnected(connected) {
    this.table.classList.toggle('stale', !connected);
  }
}

function nodeBody(node) {
  const body = document.createElement('tbody');
  body.dataset.node = node.name;
  body.dataset.state = node.state;
  body.className = DOWN_STATES.has(node.state) ? 'node-down' : `node-${node.state}`;
  const main = document.createElement('tr');
  const state = cell(node.state, 'state');
  main.append(
    state,
    cell(node.name, 'name'),
    cell(node.kind || DASH),
    cell(node.pid === null ? DASH : String(node.pid)),
    cell(duration(node.uptimeS)),
    cell(String(node.restarts), node.restarts > 0 ? 'warn' : ''),
    cell(duration(node.statusAgeS)),
  );
  const details = document.createElement('tr');
  details.className = 'counters';
  const counters = cell(Object.entries(node.counters).map(([k, v]) => `${k} ${count(v)}`).join(' · ') || 'no counters');
  counters.colSpan = 7;
  details.append(counters);
  body.append(main, details);
  return body;
}
