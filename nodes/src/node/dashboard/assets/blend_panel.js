// The Blending panel: a palette of the blend node's parts (from the hello) to drag onto the
// cloud; a drop picks the cloud point under the cursor and sends a `drop` there; sliders and keys
// send the part's absolute adjustment (spin, lift, tilt); commit and clear. Every command's
// blend_result is shown, errors in red (docs/dashboard-protocol.md, "Browser to server").

const ADJUST_SEND_INTERVAL_MS = 100; // a slider drag sends at most this often (the latest values)
const DEGREES = Math.PI / 180;
const PART_MIME = 'application/x-shroud-part';

// The on-screen adjustment controls: name, unit shown, step of a key press, range.
const ADJUSTMENTS = {
  spin: { label: 'spin', unit: '°', step: 5, min: -180, max: 180, toCommand: (v) => v * DEGREES },
  lift: { label: 'lift', unit: 'mm', step: 5, min: -200, max: 200, toCommand: (v) => v / 1000 },
  tiltA: { label: 'tilt a', unit: '°', step: 2, min: -60, max: 60, toCommand: (v) => v * DEGREES },
  tiltB: { label: 'tilt b', unit: '°', step: 2, min: -60, max: 60, toCommand: (v) => v * DEGREES },
};

export class BlendPanel {
  // elements: {root, palette, sliders, result, commit, clear}; send(message) -> bool;
  // pickPoint(clientX, clientY) -> {stream, position} | null.
  constructor(elements, { send, pickPoint }) {
    this.elements = elements;
    this.send = send;
    this.pickPoint = pickPoint;
    this.nextId = 1;
    this.pending = new Map(); // id -> description of the command
    this.placed = false; // a part is down: adjustments apply
    this.values = { spin: 0, lift: 0, tiltA: 0, tiltB: 0 };
    this.adjustTimer = null;
    this.adjustSentValues = null;
    this.inputs = this.buildSliders();
    this.showValues();
    elements.commit.addEventListener('click', () => this.commit());
    elements.clear.addEventListener('click', () => this.clear());
    this.setBlend(null);
  }

  setBlend(blend) {
    this.blend = blend;
    this.elements.root.classList.toggle('disabled', !blend);
    const items = blend ? blend.parts.map((part) => paletteItem(part)) : [];
    this.elements.palette.replaceChildren(...items);
    if (!blend) this.elements.palette.textContent = 'No blend stream: start the node with a blend stream to paste parts.';
    this.updateButtons();
  }

  buildSliders() {
    const inputs = {};
    for (const [name, spec] of Object.entries(ADJUSTMENTS)) {
      const row = document.createElement('label');
      row.className = 'slider';
      const input = document.createElement('input');
      Object.assign(input, { type: 'range', min: spec.min, max: spec.max, step: spec.step / 5, value: 0 });
      input.dataset.adjust = name;
      const shown = document.createElement('output');
      input.addEventListener('input', () => this.setAdjustment(name, Number(input.value)));
      row.append(`${spec.label}`, input, shown);
      this.elements.sliders.append(row);
      inputs[name] = { input, shown };
    }
    return inputs;
  }

  showValues() {
    for (const [name, spec] of Object.entries(ADJUSTMENTS)) {
      const control = this.inputs[name];
      control.input.value = this.values[name];
      control.shown.textContent = `${this.values[name].toFixed(name === 'lift' ? 0 : 1)} ${spec.unit}`;
    }
  }

  // A part dropped at CSS pixel (clientX, clientY) of the 3D view.
  dropAt(part, clientX, clientY) {
    if (!this.blend) return this.showLocal('no blend stream: a drop has nowhere to go', false);
    if (!this.blend.parts.includes(part)) return this.showLocal(`"${part}" is not one of the blend node's parts`, false);
    const hit = this.pickPoint(clientX, clientY);
    if (!hit) return this.showLocal('no cloud point under the cursor: drop the part onto the cloud', false);
    this.values = { spin: 0, lift: 0, tiltA: 0, tiltB: 0 };
    this.showValues();
    const at = hit.position.map((x) => +x.toFixed(5));
    if (this.command({ command: 'drop', part, at }, `drop ${part} at [${at.join(', ')}] on ${hit.stream}`)) {
      this.placed = true;
      this.updateButtons();
    }
  }

  // Sets adjustment `name` to `value` (clamped to its range) and sends the adjustment soon.
  setAdjustment(name, value) {
    const spec = ADJUSTMENTS[name];
    this.values[name] = Math.max(spec.min, Math.min(spec.max, value));
    this.showValues();
    if (this.placed) this.scheduleAdjust();
  }

  nudge(name, steps) {
    if (!this.placed) return;
    this.setAdjustment(name, this.values[name] + steps * ADJUSTMENTS[name].step);
  }

  // Sends now unless one went out within the interval; then once more at its end if changed.
  scheduleAdjust() {
    if (this.adjustTimer !== null) return;
    this.sendAdjust();
    this.adjustTimer = setTimeout(() => {
      this.adjustTimer = null;
      if (JSON.stringify(this.values) !== this.adjustSentValues) this.scheduleAdjust();
    }, ADJUST_SEND_INTERVAL_MS);
  }

  sendAdjust() {
    this.adjustSentValues = JSON.stringify(this.values);
    const v = (name) => ADJUSTMENTS[name].toCommand(this.values[name]);
    this.command({ command: 'adjust', spin: v('spin'), lift: v('lift'), tilt: [v('tiltA'), v('tiltB')] },
      `adjust ${Object.entries(ADJUSTMENTS).map(([n, s]) => `${s.label} ${this.values[n]} ${s.unit}`).join(', ')}`);
  }

  commit() {
    if (this.placed && this.command({ command: 'commit' }, 'commit')) this.placed = false;
    this.updateButtons();
  }

  clear() {
    if (this.placed && this.command({ command: 'clear' }, 'clear')) this.placed = false;
    this.updateButtons();
  }

  // Sends one blend command with a fresh id; false (and shown) when the socket is closed.
  command(fields, description) {
    const id = this.nextId++;
    if (!this.send({ type: 'blend', id, ...fields })) {
      this.showLocal(`${description}: not sent, the socket is closed`, false);
      return false;
    }
    this.pending.set(id, description);
    this.show({ text: `#${id} ${description}: sent, waiting for the node`, state: 'pending', id });
    return true;
  }

  onResult(result) {
    const description = this.pending.get(result.id);
    if (description === undefined) return; // another browser's command
    this.pending.delete(result.id);
    const text = result.ok
      ? `#${result.id} ${description}: ok, sent to the blend node`
      : `#${result.id} ${description}: failed: ${result.error || 'no reason given'}`;
    this.show({ text, state: result.ok ? 'ok' : 'error', id: result.id });
  }

  showLocal(text, ok) {
    this.show({ text, state: ok ? 'ok' : 'error', id: '' });
  }

  show({ text, state, id }) {
    const result = this.elements.result;
    result.textContent = text;
    result.dataset.state = state;
    result.dataset.id = String(id);
  }

  updateButtons() {
    this.elements.commit.disabled = !this.placed;
    this.elements.clear.disabled = !this.placed;
    this.elements.sliders.classList.toggle('disabled', !this.placed);
  }
}

function paletteItem(part) {
  const item = document.createElement('div');
  item.className = 'part';
  item.draggable = true;
  item.textContent = part;
  item.dataset.part = part;
  item.title = `drag "${part}" onto the cloud`;
  item.addEventListener('dragstart', (event) => {
    event.dataTransfer.setData(PART_MIME, part);
    event.dataTransfer.setData('text/plain', part);
    event.dataTransfer.effectAllowed = 'copy';
  });
  return item;
}

// Makes `element` (the 3D view) accept parts dragged from the palette.
export function attachDropTarget(element, panel) {
  const carriesPart = (event) => [...event.dataTransfer.types].includes(PART_MIME);
  element.addEventListener('dragover', (event) => {
    if (!carriesPart(event)) return;
    event.preventDefault();
    event.dataTransfer.dropEffect = 'copy';
    element.classList.add('drop-target');
  });
  element.addEventListener('dragleave', () => element.classList.remove('drop-target'));
  element.addEventListener('drop', (event) => {
    element.classList.remove('drop-target');
    if (!carriesPart(event)) return;
    event.preventDefault();
    panel.dropAt(event.dataTransfer.getData(PART_MIME), event.clientX, event.clientY);
  });
}
