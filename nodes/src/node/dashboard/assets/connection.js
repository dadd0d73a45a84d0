// The page's one WebSocket to the node (`/ws` on the page's own host), reopened after every
// close with exponential backoff (0.25 s doubling to 5 s, back to 0.25 s once a socket opens).

const FIRST_RETRY_MS = 250;
const LAST_RETRY_MS = 5000;

export class Connection {
  // onFrame(ArrayBuffer | string) for every message; onState({state, retryInMs}) on every change.
  constructor({ onFrame, onState }) {
    this.onFrame = onFrame;
    this.onState = onState;
    this.retryMs = FIRST_RETRY_MS;
    this.socket = null;
    this.url = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`;
  }

  open() {
    this.onState({ state: 'connecting' });
    const socket = new WebSocket(this.url);
    socket.binaryType = 'arraybuffer';
    socket.onopen = () => {
      this.retryMs = FIRST_RETRY_MS;
      this.onState({ state: 'open' });
    };
    socket.onmessage = (event) => this.onFrame(event.data);
    // An error is always followed by close; the retry is scheduled there, once.
    socket.onerror = () => {};
    socket.onclose = () => this.scheduleRetry();
    this.socket = socket;
  }

  scheduleRetry() {
    const delay = this.retryMs;
    this.retryMs = Math.min(this.retryMs * 2, LAST_RETRY_MS);
    this.onState({ state: 'closed', retryInMs: delay });
    setTimeout(() => this.open(), delay);
  }

  get isOpen() {
    return this.socket !== null && this.socket.readyState === WebSocket.OPEN;
  }

  // Sends one JSON text frame; false when the socket is not open (the caller shows that).
  send(message) {
    if (!this.isOpen) return false;
    this.socket.send(JSON.stringify(message));
    return true;
  }
}
