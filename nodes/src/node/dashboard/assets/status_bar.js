// The header's status: connection state, namespace, frames received, malformed frames (with the
// last problem, so a bad frame is shown, never silently lost), frames of unknown type (ignored
// by design) and the node's own dashboard counters.

import { PROTOCOL_VERSION } from './protocol.js';

export class StatusBar {
  constructor(elements) {
    this.elements = elements; // {connection, namespace, frames, malformed, serverError}
    this.frames = 0;
    this.malformed = 0;
    this.unknown = 0;
  }

  setConnection({ state, retryInMs }) {
    const { connection } = this.elements;
    connection.dataset.state = state;
    connection.textContent = state === 'open' ? 'connected'
      : state === 'connecting' ? 'connecting…' : `disconnected, retrying in ${(retryInMs / 1000).toFixed(2)} s`;
  }

  onHello(hello) {
    this.elements.namespace.textContent = `namespace ${hello.namespace || '–'}`;
    if (hello.protocol !== PROTOCOL_VERSION) {
      this.showServerError(`the node speaks protocol ${hello.protocol}, this page ${PROTOCOL_VERSION}`);
    }
  }

  countFrame() {
    this.frames++;
  }

  countUnknown() {
    this.unknown++;
  }

  countMalformed(problem) {
    this.malformed++;
    const { malformed } = this.elements;
    malformed.hidden = false;
    malformed.textContent = `${this.malformed} malformed`;
    malformed.title = `last: ${problem}`;
    malformed.dataset.last = problem;
  }

  showServerError(message) {
    this.elements.serverError.hidden = false;
    this.elements.serverError.textContent = `node: ${message}`;
  }

  // Refreshed a few times a second, with the node's counters from the latest `nodes`.
  refresh(dashboard) {
    const parts = [`${this.frames.toLocaleString('en-US')} frames`];
    if (this.unknown > 0) parts.push(`${this.unknown} of unknown type ignored`);
    if (dashboard && typeof dashboard.frames_superseded === 'number') {
      parts.push(`${dashboard.frames_superseded.toLocaleString('en-US')} superseded at the node`);
    }
    this.elements.frames.textContent = parts.join(' · ');
  }
}
