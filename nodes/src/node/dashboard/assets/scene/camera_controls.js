// Mouse and wheel on the 3D view: left drag orbits, right drag (or shift + left, or middle) pans,
// the wheel zooms toward the target. Keys are bound in ../keys.js.

const ORBIT_RADIANS_PER_PIXEL = 0.008;
const ZOOM_PER_WHEEL_PIXEL = 1.0015;

export function attachCameraControls(canvas, view) {
  let drag = null; // {mode, x, y}
  canvas.addEventListener('contextmenu', (event) => event.preventDefault());
  canvas.addEventListener('pointerdown', (event) => {
    const pan = event.button === 2 || event.button === 1 || (event.button === 0 && event.shiftKey);
    drag = { mode: pan ? 'pan' : 'orbit', x: event.clientX, y: event.clientY };
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    const dx = event.clientX - drag.x;
    const dy = event.clientY - drag.y;
    drag.x = event.clientX;
    drag.y = event.clientY;
    if (drag.mode === 'orbit') {
      view.camera.orbit(dx * ORBIT_RADIANS_PER_PIXEL, dy * ORBIT_RADIANS_PER_PIXEL);
    } else {
      view.camera.pan(dx / canvas.clientHeight, dy / canvas.clientHeight);
    }
    view.cameraMovedByUser();
  });
  const endDrag = (event) => {
    drag = null;
    if (canvas.hasPointerCapture(event.pointerId)) canvas.releasePointerCapture(event.pointerId);
  };
  canvas.addEventListener('pointerup', endDrag);
  canvas.addEventListener('pointercancel', endDrag);
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    view.camera.zoom(ZOOM_PER_WHEEL_PIXEL ** event.deltaY);
    view.cameraMovedByUser();
  }, { passive: false });
}
