// page_state.js: the page's elements, its state and the address's hash (#light=30,40&zoom=1&
// view=2d|sphere&ui=0). The first of the page's four parts (page_state, page_draw, page_panel,
// page_input), which src/apps/cli/web_page.cpp joins, in that order, into one strict function
// after btflut_material.js: each uses the others' names.
//
// The page: the viewer of the page `btflut export --web` writes. The material's files are in
// the page (data: URLs); btflut_material.js reads them, WebGL2 draws them through the engine
// include's GLSL ES form. A 2D view (pan, zoom, 1:1) and a sphere under a point light; the
// light dragged on the disk of directions, by keys or by touch. State in the address's hash.
const data = window.btflutPage;  // set by the page's first script
const json = data.material;
const view = document.getElementById('view'), panel = document.getElementById('panel');
const diskCanvas = document.getElementById('disk');

function showMessage(text) {
  const box = document.getElementById('message');
  box.textContent = text;
  box.style.display = 'flex';
  panel.style.display = 'none';
}

// --- State, and the address's hash -------------------------------------------------------
const state = {theta: 30, phi: 45, zoom: null, centre: null, view: '2d', ui: true, exposure: 1, anchored: false};
function readHash() {
  const fields = Object.fromEntries(location.hash.slice(1).split('&').filter(Boolean).map((p) => p.split('=').map(decodeURIComponent)));
  const [theta, phi] = (fields.light || '').split(',').map(Number);
  if (fields.light && Number.isFinite(theta) && Number.isFinite(phi)) state.theta = Math.min(89.9, Math.max(0, theta)), state.phi = phi;
  else if (!fields.light) defaultLight();
  if (fields.zoom) state.zoom = fields.zoom === 'fit' ? null : Math.min(64, Math.max(1 / 64, Number(fields.zoom) || 1));
  if (fields.view === 'sphere' || fields.view === '2d') state.view = fields.view;
  if (fields.ui !== undefined) state.ui = fields.ui !== '0';
  if (fields.exposure && Number(fields.exposure) > 0) state.exposure = Number(fields.exposure);
  state.anchored = !state.ui;  // ui=0: the material at the top left, as a screenshot wants it
}
function writeHash() {
  const zoom = state.zoom === null ? 'fit' : +state.zoom.toFixed(4);
  const hash = '#light=' + (+state.theta.toFixed(2)) + ',' + (+state.phi.toFixed(2)) + '&zoom=' + zoom + '&view=' + state.view +
               (state.ui ? '' : '&ui=0') + (state.exposure === 1 ? '' : '&exposure=' + (+state.exposure.toFixed(3)));
  try { history.replaceState(null, '', hash); } catch (e) { /* some file:// pages refuse: the state still works */ }
}
