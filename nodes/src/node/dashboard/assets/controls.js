// The 3D view's toolbar: colour mode, point size, layer toggles, preset views, pause, and this
// browser's point budget (sent to the node as an `options` message), plus the help overlay.

import { COLOR_MODES } from './scene/points.js';

const POINT_SIZE = { min: 1, max: 12 };

export class ViewControls {
  // elements: {toolbar, colorMode, pointSize, pointSizeShown, pause, budget, budgetShown, help, helpButton}
  constructor(elements, { view, send }) {
    this.elements = elements;
    this.view = view;
    this.send = send;
    const e = elements;
    e.colorMode.addEventListener('change', () => this.setColorMode(e.colorMode.value));
    e.pointSize.addEventListener('input', () => this.setPointSize(Number(e.pointSize.value)));
    e.pause.addEventListener('click', () => this.togglePause());
    e.helpButton.addEventListener('click', () => this.toggleHelp());
    e.budget.addEventListener('change', () => {
      this.budgetChosen = true;
      this.sendBudget();
    });
    for (const button of e.toolbar.querySelectorAll('[data-view]')) {
      button.addEventListener('click', () => view?.setView(button.dataset.view));
    }
    for (const box of e.toolbar.querySelectorAll('[data-layer]')) {
      box.addEventListener('change', () => view?.setVisible(box.dataset.layer, box.checked));
    }
    this.setPointSize(Number(e.pointSize.value));
  }

  setColorMode(mode) {
    this.elements.colorMode.value = mode;
    this.view?.setOption('colorMode', mode);
    document.body.dataset.colorMode = mode; // the legend shows the matching key
  }

  cycleColorMode() {
    const next = COLOR_MODES[(COLOR_MODES.indexOf(this.elements.colorMode.value) + 1) % COLOR_MODES.length];
    this.setColorMode(next);
  }

  setPointSize(size) {
    const clamped = Math.max(POINT_SIZE.min, Math.min(POINT_SIZE.max, size));
    this.elements.pointSize.value = clamped;
    this.elements.pointSizeShown.textContent = `${clamped} px`;
    this.view?.setOption('pointSize', clamped);
  }

  stepPointSize(step) {
    this.setPointSize(Number(this.elements.pointSize.value) + step);
  }

  toggleLayer(layer) {
    const box = this.elements.toolbar.querySelector(`[data-layer="${layer}"]`);
    box.checked = !box.checked;
    this.view?.setVisible(layer, box.checked);
  }

  togglePause() {
    const paused = !this.elements.pause.classList.contains('active');
    this.elements.pause.classList.toggle('active', paused);
    this.elements.pause.textContent = paused ? 'Resume' : 'Pause';
    this.view?.setOption('paused', paused);
  }

  toggleHelp() {
    this.elements.help.hidden = !this.elements.help.hidden;
  }

  // The node's --point-budget caps the range (docs/dashboard-protocol.md: 1000 to the node's budget).
  setBudgetLimit(limit) {
    if (limit === null) return;
    const { budget } = this.elements;
    budget.max = limit;
    if (Number(budget.value) === 0 || Number(budget.value) > limit) budget.value = limit;
    this.elements.budgetShown.textContent = `of ${Number(limit).toLocaleString('en-US')}`;
  }

  // A new connection starts at the node's budget: send this browser's choice again.
  onHello(hello) {
    this.setBudgetLimit(hello.pointBudget);
    if (this.budgetChosen) this.sendBudget();
  }

  sendBudget() {
    const { budget } = this.elements;
    const value = Math.round(Math.max(1000, Math.min(Number(budget.max) || Infinity, Number(budget.value) || 1000)));
    budget.value = value;
    this.send({ type: 'options', point_budget: value });
  }
}
