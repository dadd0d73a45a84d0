// The keyboard shortcuts: one table that both binds the keys and writes the help, so the help
// always says what the keys do. Keys are ignored while typing in a field.

// Each binding: {keys: [KeyboardEvent.key values], label shown in the help, action()}.
export function keyBindings({ view, controls, blend }) {
  return [
    { keys: ['0', 'Home'], label: 'reset view (fit the clouds and follow them)', action: () => view?.setView('reset') },
    { keys: ['1'], label: 'top view', action: () => view?.setView('top') },
    { keys: ['2'], label: 'front view (along −x)', action: () => view?.setView('front') },
    { keys: ['3'], label: 'side view (along +y)', action: () => view?.setView('side') },
    { keys: [' '], label: 'pause / resume the 3D view', action: () => controls.togglePause() },
    { keys: ['+', '='], label: 'larger points', action: () => controls.stepPointSize(1) },
    { keys: ['-'], label: 'smaller points', action: () => controls.stepPointSize(-1) },
    { keys: ['c'], label: 'colour by height → intensity → source', action: () => controls.cycleColorMode() },
    { keys: ['u'], label: 'upper surfaces on / off', action: () => controls.toggleLayer('upper') },
    { keys: ['b'], label: 'lower (bottom) surfaces on / off', action: () => controls.toggleLayer('lower') },
    { keys: ['g'], label: 'smooth (G1) surfaces on / off', action: () => controls.toggleLayer('smooth') },
    { keys: ['a'], label: 'arm on / off', action: () => controls.toggleLayer('arm') },
    { keys: ['q', 'e'], label: 'blend: spin the part − / +', action: (key) => blend.nudge('spin', key === 'q' ? -1 : 1) },
    { keys: ['r', 'f'], label: 'blend: lift the part + / −', action: (key) => blend.nudge('lift', key === 'r' ? 1 : -1) },
    { keys: ['i', 'k'], label: 'blend: tilt a + / −', action: (key) => blend.nudge('tiltA', key === 'i' ? 1 : -1) },
    { keys: ['j', 'l'], label: 'blend: tilt b − / +', action: (key) => blend.nudge('tiltB', key === 'j' ? -1 : 1) },
    { keys: ['Enter'], label: 'blend: commit the part', action: () => blend.commit() },
    { keys: ['x'], label: 'blend: clear the part', action: () => blend.clear() },
    { keys: ['h', '?'], label: 'show / hide this help', action: () => controls.toggleHelp() },
  ];
}

export function attachKeys(bindings) {
  const byKey = new Map(bindings.flatMap((binding) => binding.keys.map((key) => [key, binding])));
  window.addEventListener('keydown', (event) => {
    const target = event.target;
    const typing = target instanceof HTMLElement &&
      target.closest('textarea, select, input:not([type=range]):not([type=checkbox])');
    if (typing || event.ctrlKey || event.metaKey || event.altKey) return;
    const key = event.key.length === 1 ? event.key.toLowerCase() : event.key;
    // A focused button takes Space and Enter itself.
    if (target instanceof HTMLButtonElement && (key === ' ' || key === 'Enter')) return;
    const binding = byKey.get(key);
    if (!binding) return;
    event.preventDefault();
    binding.action(key);
  });
}

const keyName = (key) => ({ ' ': 'Space', Home: 'Home', Enter: 'Enter' })[key] ?? key.toUpperCase();

// Writes the key table into `list` (a <dl>).
export function renderKeyHelp(list, bindings) {
  for (const binding of bindings) {
    const keys = document.createElement('dt');
    for (const key of binding.keys) {
      const kbd = document.createElement('kbd');
      kbd.textContent = keyName(key);
      keys.append(kbd);
    }
    const label = document.createElement('dd');
    label.textContent = binding.label;
    list.append(keys, label);
  }
}
