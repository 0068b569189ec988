// page_panel.js: the panel's facts and the disk of light directions (measured, clamped and
// modelled ones marked). Third of the page's parts (page_state.js).
// --- The panel and the light disk ---------------------------------------------------------
const layer = (json.views || [])[0] || {};
// The provenance of the grid node nearest the light (the export's node_provenance).
function lightProvenance() {
  const g = json.luts.grid_size, provenance = layer.node_provenance || [];
  const r = Math.SQRT2 * Math.sin(state.theta * Math.PI / 360);
  const x = r * Math.cos(state.phi * Math.PI / 180), y = r * Math.sin(state.phi * Math.PI / 180);
  const i = Math.round((x + 1) / 2 * (g - 1)), j = Math.round((y + 1) / 2 * (g - 1));
  return provenance[j * g + i] || 'measured';
}
// The light a page opens at without #light: (30, 45), unless that is beyond the measured lights
// (a narrow capture), then the measured light nearest it on the disk.
function defaultLight() {
  state.theta = 30; state.phi = 45;
  if (!['clamped', 'extrapolated'].includes(lightProvenance())) return;
  const [x0, y0] = diskPoint(30, 45);
  let best = Infinity;
  for (const node of layer.lights || []) {
    if (node.modelled) continue;
    const [x, y] = diskPoint(node.theta, node.phi), d = Math.hypot(x - x0, y - y0);
    if (d < best) best = d, state.theta = node.theta, state.phi = node.phi;
  }
}
function updatePanel() {
  panel.style.display = state.ui ? 'block' : 'none';
  const beyond = ['clamped', 'extrapolated'].includes(lightProvenance());  // 'extrapolated': older exports
  document.getElementById('light').textContent = 'theta ' + state.theta.toFixed(1) + ', phi ' + state.phi.toFixed(1) +
      (beyond ? ' (clamped: beyond the measured lights; bake --fill model fills them)' : '');
  document.getElementById('exposure-value').textContent = state.exposure.toFixed(2);
  document.getElementById('exposure').value = Math.log2(state.exposure);
  document.getElementById('view-2d').classList.toggle('on', state.view === '2d');
  document.getElementById('view-sphere').classList.toggle('on', state.view === 'sphere');
}
// The equal-area disk (as btflut's grid): r = sqrt(2) sin(theta / 2), the horizon at r = 1.
const diskRadius = 88, diskCentre = 96;
function diskPoint(theta, phi) {
  const r = Math.SQRT2 * Math.sin(theta * Math.PI / 360) * diskRadius;
  return [diskCentre + r * Math.cos(phi * Math.PI / 180), diskCentre - r * Math.sin(phi * Math.PI / 180)];
}
function drawDisk() {
  if (!state.ui) return;
  const c = diskCanvas.getContext('2d');
  c.clearRect(0, 0, 192, 192);
  c.fillStyle = '#1c2230';
  c.beginPath(); c.arc(diskCentre, diskCentre, diskRadius, 0, 2 * Math.PI); c.fill();
  // Grid nodes the engine export draws from something other than measurements.
  const g = json.luts.grid_size, provenance = layer.node_provenance || [];
  const cell = 2 * diskRadius / (g - 1);
  c.save();
  c.beginPath(); c.arc(diskCentre, diskCentre, diskRadius, 0, 2 * Math.PI); c.clip();
  provenance.forEach((kind, k) => {
    if (kind !== 'modelled' && kind !== 'clamped' && kind !== 'extrapolated') return;  // 'extrapolated': exports before 2026-12
    const i = k % g, j = Math.floor(k / g), x = -1 + 2 * i / (g - 1), y = -1 + 2 * j / (g - 1);
    c.fillStyle = kind === 'modelled' ? 'rgba(230, 140, 40, 0.45)' : 'rgba(150, 150, 150, 0.35)';
    c.fillRect(diskCentre + x * diskRadius - cell / 2, diskCentre - y * diskRadius - cell / 2, cell, cell);
  });
  c.restore();
  for (const node of layer.lights || []) {
    const [x, y] = diskPoint(node.theta, node.phi);
    c.fillStyle = node.modelled ? '#e68c28' : '#fff';
    c.beginPath(); c.arc(x, y, 2.5, 0, 2 * Math.PI); c.fill();
  }
  c.strokeStyle = '#667'; c.lineWidth = 1;
  c.beginPath(); c.arc(diskCentre, diskCentre, diskRadius, 0, 2 * Math.PI); c.stroke();
  const [lx, ly] = diskPoint(state.theta, state.phi);
  c.strokeStyle = '#ffd54a'; c.lineWidth = 2;
  c.beginPath(); c.arc(lx, ly, 6, 0, 2 * Math.PI); c.stroke();
}
function setLightFromDisk(event) {
  const rect = diskCanvas.getBoundingClientRect();
  const x = ((event.clientX - rect.left) * 192 / rect.width - diskCentre) / diskRadius;
  const y = -((event.clientY - rect.top) * 192 / rect.height - diskCentre) / diskRadius;
  const r = Math.min(1, Math.hypot(x, y));
  state.theta = Math.min(89.9, 2 * Math.asin(r / Math.SQRT2) * 180 / Math.PI);
  state.phi = (Math.atan2(y, x) * 180 / Math.PI + 360) % 360;
  redraw();
}
