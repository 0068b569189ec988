// page_input.js: pointer (mouse, touch, pen), wheel, keys and buttons, then the start. Last of
// the page's parts (page_state.js).
// --- Input: pointer (mouse, touch, pen), wheel, keys, buttons ---------------------------
const pointers = new Map();
let pinch = null;
diskCanvas.addEventListener('pointerdown', (e) => { diskCanvas.setPointerCapture(e.pointerId); setLightFromDisk(e); });
diskCanvas.addEventListener('pointermove', (e) => { if (diskCanvas.hasPointerCapture(e.pointerId)) setLightFromDisk(e); });
function zoomAt(factor, clientX, clientY) {
  if (state.view !== '2d') return;
  const dpr = window.devicePixelRatio || 1, zoom = state.zoom === null ? fitZoom() : state.zoom;
  const next = Math.min(64, Math.max(1 / 64, zoom * factor));
  if (clientX !== undefined) {  // the texel under the cursor stays there
    const px = clientX * dpr - view.width / 2, py = (view.clientHeight - clientY) * dpr - view.height / 2;
    state.centre = [state.centre[0] + px / zoom - px / next, state.centre[1] + py / zoom - py / next];
  }
  state.zoom = next;
  state.anchored = false;
  redraw();
}
view.addEventListener('pointerdown', (e) => { view.setPointerCapture(e.pointerId); pointers.set(e.pointerId, [e.clientX, e.clientY]); });
view.addEventListener('pointerup', (e) => { pointers.delete(e.pointerId); pinch = null; });
view.addEventListener('pointercancel', (e) => { pointers.delete(e.pointerId); pinch = null; });
view.addEventListener('pointermove', (e) => {
  if (!pointers.has(e.pointerId)) return;
  const [x0, y0] = pointers.get(e.pointerId);
  pointers.set(e.pointerId, [e.clientX, e.clientY]);
  if (pointers.size === 2) {  // pinch: zoom about the fingers' midpoint
    const [a, b] = [...pointers.values()];
    const spread = Math.hypot(a[0] - b[0], a[1] - b[1]);
    if (pinch) zoomAt(spread / pinch, (a[0] + b[0]) / 2, (a[1] + b[1]) / 2);
    pinch = spread;
    return;
  }
  const dpr = window.devicePixelRatio || 1;
  if (state.view === 'sphere') {  // drag the point light across the sphere's front
    const v = lightVector(), speed = 0.01;
    const x = v[0] + (e.clientX - x0) * speed, y = v[1] - (e.clientY - y0) * speed;
    const r = Math.min(0.9998, Math.hypot(x, y));
    state.theta = Math.asin(r) * 180 / Math.PI;
    state.phi = (Math.atan2(y, x) * 180 / Math.PI + 360) % 360;
  } else {
    if (state.zoom === null) state.zoom = fitZoom();  // a fitted view, once panned, keeps its zoom
    const zoom = state.zoom;
    if (state.anchored) state.centre = [view.width / 2 / zoom, state.size[1] - view.height / 2 / zoom], state.anchored = false;
    state.centre = [state.centre[0] - (e.clientX - x0) * dpr / zoom, state.centre[1] + (e.clientY - y0) * dpr / zoom];
  }
  redraw();
});
view.addEventListener('wheel', (e) => { e.preventDefault(); zoomAt(Math.pow(1.0015, -e.deltaY), e.clientX, e.clientY); }, {passive: false});
window.addEventListener('keydown', (e) => {
  const step = e.shiftKey ? 1 : 5;
  const actions = {
    ArrowLeft: () => { state.phi = (state.phi + step) % 360; }, ArrowRight: () => { state.phi = (state.phi - step + 360) % 360; },
    ArrowUp: () => { state.theta = Math.max(0, state.theta - step); }, ArrowDown: () => { state.theta = Math.min(89.9, state.theta + step); },
    '+': () => zoomAt(1.25), '=': () => zoomAt(1.25), '-': () => zoomAt(0.8),
    '1': () => { state.zoom = 1; state.anchored = false; }, f: () => { state.zoom = null; state.centre = null; state.anchored = false; },
    s: () => { state.view = state.view === 'sphere' ? '2d' : 'sphere'; }, u: () => { state.ui = !state.ui; },
    e: () => { state.exposure = Math.min(4, state.exposure * 1.25); }, E: () => { state.exposure = Math.max(0.25, state.exposure / 1.25); }};
  const action = actions[e.key];
  if (!action || e.ctrlKey || e.metaKey || e.altKey) return;
  e.preventDefault();
  action();
  redraw();
});
const click = (id, action) => document.getElementById(id).addEventListener('click', () => { action(); redraw(); });
click('view-2d', () => { state.view = '2d'; });
click('view-sphere', () => { state.view = 'sphere'; });
click('one', () => { state.zoom = 1; state.view = '2d'; state.anchored = false; });
click('fit', () => { state.zoom = null; state.centre = null; state.view = '2d'; state.anchored = false; });
document.getElementById('exposure').addEventListener('input', (e) => { state.exposure = Math.pow(2, Number(e.target.value)); redraw(); });
window.addEventListener('resize', redraw);
window.addEventListener('hashchange', () => { readHash(); redraw(); });

// --- Start -----------------------------------------------------------------------------------
const name = data.name || json.reference.name || 'material';
document.title = name + ' (btflut)';
document.getElementById('name').textContent = name;
document.getElementById('facts').textContent = json.reference.width + ' x ' + json.reference.height + ' texels, ' + json.kind +
  (json.predictor ? ' (' + (json.predictor.name || json.predictor.basis || 'references') + ')' : '') + ', ' + json.luts.grid_size + ' x ' +
  json.luts.grid_size + ' light grid' + (data.bytes ? ', ' + (data.bytes / 1024).toFixed(0) + ' KB exported' : '');
readHash();
load().then(draw).catch((e) => {
  console.error(String(e && e.message || e));
  showMessage('This material could not be drawn: ' + String(e && e.message || e));
});
