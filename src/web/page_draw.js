// page_draw.js: WebGL2 drawing: the program from the include's GLSL ES form, the material's
// textures (load), the 2D view and the sphere (draw). Second of the page's parts (page_state.js).
// --- WebGL2 ----------------------------------------------------------------------------------
const gl = view.getContext('webgl2', {antialias: false, preserveDrawingBuffer: true});
if (!gl) {
  showMessage('This page needs WebGL2 to relight the material, and this browser does not offer it ' +
              '(it may be switched off, or the graphics driver blocked). Try another browser, or enable hardware acceleration.');
  return;
}
const vertexSource = `#version 300 es
void main() {
  vec2 corner = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);  // one triangle covers the view
  gl_Position = vec4(corner, 0.0, 1.0);
}`;
const fragmentMain = btflutMaterial.fragmentHead + `
uniform int mode;            // 0: 2D, 1: sphere
uniform vec2 origin;         // 2D: the view pixel of texel (0, 0)'s corner, GL's y up
uniform float zoom;          // 2D: view pixels per texel
uniform vec3 sphere;         // centre (view pixels) and radius
uniform vec2 tiles;          // sphere: the window's repeats around (even) and up
uniform vec4 window;         // sphere: the sample's rectangle in texture coordinates (x, y, width, height)
uniform vec3 light;          // 2D: the direction; sphere: towards the point light (from the centre)
uniform float lightDistance; // sphere: the point light's distance from the centre, in radii
uniform float exposure;
out vec4 colour;

void main() {
  colour = vec4(0.0, 0.0, 0.0, 1.0);
  if (mode == 0) {
      vec2 t = (gl_FragCoord.xy - origin) / zoom;  // texture texels, rows bottom first
      if (any(lessThan(t, vec2(0.0))) || any(greaterThanEqual(t, size))) return;
      vec2 texel = floor(t);
      uvec2 pixel = uvec2(texel.x, size.y - 1.0 - texel.y);  // image rows top first: btflut's dither
      colour.rgb = min(relight(t / size, light, pixel) * exposure, 1.0);
      return;
  }
  vec2 p = (gl_FragCoord.xy - sphere.xy) / sphere.z;
  float rr = dot(p, p);
  if (rr >= 1.0) return;
  vec3 n = vec3(p, sqrt(1.0 - rr));
  float longitude = atan(n.x, n.z), latitude = asin(clamp(n.y, -1.0, 1.0));
  // The sample's window repeated mirrored (every other tile flipped), so tiles meet without
  // seams and the mask's background never shows. The tangent frame is not flipped with it:
  // both sides of a seam see the light alike, so the seam does not show in the shading either.
  vec2 t = vec2(longitude / 6.2831853 * tiles.x, (latitude / 3.1415927 + 0.5) * tiles.y);
  vec2 f = fract(t), local = mix(f, 1.0 - f, mod(floor(t), 2.0));
  vec2 uv = window.xy + local * window.zw;
  vec3 u = vec3(cos(longitude), 0.0, -sin(longitude)), v = cross(n, u);  // the tangent frame: +u, +v, the normal
  vec3 eye = vec3(0.0, 0.0, 1.0);  // the orthographic camera's direction
  vec3 towards = light * lightDistance - n;
  float d = length(towards);
  vec3 l = towards / d;
  float falloff = pow((lightDistance - 1.0) / d, 2.0);  // 1 at the surface point nearest the light
  colour.rgb = min(relight(uv, vec3(dot(l, u), dot(l, v), dot(l, n)), vec3(dot(eye, u), dot(eye, v), dot(eye, n)),
                           uvec2(gl_FragCoord.xy)) * falloff * exposure, 1.0);
}`;

function compile(type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error('shader: ' + gl.getShaderInfoLog(shader));
  return shader;
}
let program = null, uniforms = {}, material = null;
const textures = [];

function texture(target, unit, setup) {
  const t = gl.createTexture();
  gl.activeTexture(gl.TEXTURE0 + unit);
  gl.bindTexture(target, t);
  setup();
  textures.push(t);
  return t;
}
function parameters(target, filter, wrap) {
  gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, filter);
  gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, filter);
  for (const p of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T, gl.TEXTURE_WRAP_R]) gl.texParameteri(target, p, wrap);
}
function image2D(unit, image, filter) {
  texture(gl.TEXTURE_2D, unit, () => {
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    const half = image.rgba instanceof Uint16Array;
    gl.texImage2D(gl.TEXTURE_2D, 0, half ? gl.RGBA16F : gl.RGBA8, image.width, image.height, 0, gl.RGBA,
                  half ? gl.HALF_FLOAT : gl.UNSIGNED_BYTE, image.rgba);
    parameters(gl.TEXTURE_2D, filter, gl.REPEAT);
  });
}
function array2D(unit, width, height, layers, internal, type, pixels, filter) {
  texture(gl.TEXTURE_2D_ARRAY, unit, () => {
    gl.texImage3D(gl.TEXTURE_2D_ARRAY, 0, internal, width, height, layers, 0, gl.RGBA, type, pixels);
    parameters(gl.TEXTURE_2D_ARRAY, filter, gl.REPEAT);
  });
}

async function load() {
  const read = async (file) => {
    const url = data.files[file];
    if (!url) throw new Error(file + ': not in this page');
    const text = atob(url.slice(url.indexOf(',') + 1)), bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return bytes;
  };
  const m = await btflutMaterial.prepare(json, read, data.include);
  program = gl.createProgram();
  gl.attachShader(program, compile(gl.VERTEX_SHADER, vertexSource));
  gl.attachShader(program, compile(gl.FRAGMENT_SHADER,
                                   '#version 300 es\n' + btflutMaterial.shaderStart(m, data.include) + fragmentMain));
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error('program: ' + gl.getProgramInfoLog(program));
  gl.useProgram(program);
  const at = (name) => gl.getUniformLocation(program, name);
  // Units: 0 luts, 1 reference, 2 planes, 3 weights, 4 labels; a 1-texel stand-in where unused.
  texture(gl.TEXTURE_3D, 0, () => {
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 2);
    const one = m.luts.channels === 1;
    gl.texImage3D(gl.TEXTURE_3D, 0, one ? gl.R16F : gl.RGBA16F, m.luts.width, m.luts.height, m.luts.depth, 0,
                  one ? gl.RED : gl.RGBA, gl.HALF_FLOAT, m.luts.halves);
    parameters(gl.TEXTURE_3D, gl.LINEAR, gl.CLAMP_TO_EDGE);
  });
  const none = {width: 1, height: 1, rgba: new Uint8Array(4)};
  image2D(1, m.reference || none, gl.LINEAR);
  if (m.planes) array2D(2, m.planes.width, m.planes.height, m.planes.layers, gl.RGBA8, gl.UNSIGNED_BYTE, m.planes.rgba, gl.LINEAR);
  else array2D(2, 1, 1, 1, gl.RGBA8, gl.UNSIGNED_BYTE, new Uint8Array(4), gl.NEAREST);
  if (m.weights) array2D(3, m.weights.size, m.weights.size, m.weights.layers, gl.RGBA32F, gl.FLOAT, m.weights.data, gl.NEAREST);
  else array2D(3, 1, 1, 1, gl.RGBA32F, gl.FLOAT, new Float32Array(4), gl.NEAREST);
  image2D(4, m.labels || none, gl.NEAREST);
  ['luts', 'reference', 'planes', 'weights', 'labels'].forEach((name, unit) => gl.uniform1i(at(name), unit));
  const floats = ['inputCode', 'outputCode', 'codes'];  // the structs' other fields are ints and bools
  for (const [struct, values] of [['material', m.material], ['predictor', m.predictor]])
    for (const [key, value] of Object.entries(values)) {
      const location = at(struct + '.' + key + (Array.isArray(value) ? '[0]' : ''));
      if (Array.isArray(value)) gl.uniform1fv(location, value);
      else if (floats.includes(key)) gl.uniform1f(location, value);
      else gl.uniform1i(location, Number(value));
    }
  gl.uniform1i(at('hasPredictor'), m.kind !== 'luts');
  gl.uniform2f(at('size'), m.size[0], m.size[1]);
  gl.uniform1i(at('layers'), m.layerViews.length / 3);
  if (m.layerViews.length) gl.uniform3fv(at('layerViews[0]'), m.layerViews);
  uniforms = {};  // this program's; the predictor's per-light ones are looked up when first set (draw)
  for (const name of ['mode', 'origin', 'zoom', 'sphere', 'tiles', 'window', 'light', 'lightDistance', 'exposure',
                      'framePerFragment'])
    uniforms[name] = at(name);
  material = m;
  state.size = m.size;
  state.sample = m.json.sample || null;  // the sample's rectangle, for the sphere
  const error = gl.getError();
  if (error !== gl.NO_ERROR) throw new Error('WebGL error ' + error + ' while uploading the material');
}

// --- Drawing ---------------------------------------------------------------------------------
function lightVector() {
  const t = state.theta * Math.PI / 180, p = state.phi * Math.PI / 180;
  return [Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t)];
}
// The part of the view the panel leaves free, in device pixels, y up (GL's): right of the panel
// or below it, whichever shows the material larger; the whole view when the panel is hidden.
function freeArea() {
  const whole = {x: 0, y: 0, width: view.width, height: view.height};
  if (!state.ui) return whole;
  const dpr = window.devicePixelRatio || 1, box = panel.getBoundingClientRect(), [w, h] = state.size;
  const right = {x: box.right * dpr, y: 0, width: view.width - box.right * dpr, height: view.height};
  const below = {x: 0, y: 0, width: view.width, height: view.height - box.bottom * dpr};
  const scale = (a) => Math.min(a.width / w, a.height / h);
  const best = scale(right) >= scale(below) ? right : below;
  return best.width > 0 && best.height > 0 ? best : whole;
}
// "Fit": the material as large as the free area holds it, centred in it.
function fitZoom(a = freeArea()) {
  const [w, h] = state.size;
  return Math.min(a.width / w, a.height / h) * 0.95;
}
// The texel at the view's centre that puts the material's centre at the free area's.
function fitCentre(zoom, a = freeArea()) {
  const [w, h] = state.size;
  return [w / 2 - (a.x + a.width / 2 - view.width / 2) / zoom, h / 2 - (a.y + a.height / 2 - view.height / 2) / zoom];
}
let pending = false;
function redraw() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); });
}
function draw() {
  const dpr = window.devicePixelRatio || 1;
  const width = Math.max(1, Math.round(view.clientWidth * dpr)), height = Math.max(1, Math.round(view.clientHeight * dpr));
  if (view.width !== width || view.height !== height) view.width = width, view.height = height;
  gl.viewport(0, 0, width, height);
  const [w, h] = state.size;
  const free = state.zoom === null ? freeArea() : null;  // the panel's box asked once a frame
  const zoom = state.zoom === null ? fitZoom(free) : state.zoom;
  if (state.zoom === null) state.centre = fitCentre(zoom, free);  // fitted anew to every size
  if (!state.centre) state.centre = [w / 2, h / 2];
  let origin = [width / 2 - state.centre[0] * zoom, height / 2 - state.centre[1] * zoom];
  if (state.anchored) origin = [0, height - h * zoom];  // the image's top left at the view's
  if (Number.isInteger(zoom)) origin = origin.map(Math.round);  // texel centres on pixel centres
  const radius = Math.min(width, height) * 0.42;
  gl.uniform1i(uniforms.mode, state.view === 'sphere' ? 1 : 0);
  gl.uniform2f(uniforms.origin, origin[0], origin[1]);
  gl.uniform1f(uniforms.zoom, zoom);
  gl.uniform3f(uniforms.sphere, width / 2, height / 2, radius);
  // The sphere wraps the sample's rectangle (material.json's "sample"; else the whole image),
  // texels about square, an even count around so that the mirrored tiles close up.
  const sample = state.sample || {x: 0, y: 0, width: w, height: h};
  // From its first texels' centres to its last's: bilinear filtering never reaches outside it.
  gl.uniform4f(uniforms.window, (sample.x + 0.5) / w, (h - sample.y - sample.height + 0.5) / h,
               Math.max(0, sample.width - 1) / w, Math.max(0, sample.height - 1) / h);
  gl.uniform2f(uniforms.tiles, 2 * Math.max(1, Math.round(Math.PI * radius / sample.width)),
               Math.max(1, Math.round(Math.PI * radius / sample.height)));
  gl.uniform3f(uniforms.light, ...lightVector());
  // The predictor's uniforms at the light (a learned decoder's frame): here once for the 2D view,
  // per fragment on the sphere (framePerFragment: a uniform only such a decoder's shader has).
  const frame = btflutMaterial.frameUniforms(material, lightVector(), [0, 0, 1]);
  if (frame.length) gl.uniform1i(uniforms.framePerFragment, state.view === 'sphere' ? 1 : 0);
  for (const [name, size, values] of frame) {
    const location = uniforms[name] ??= gl.getUniformLocation(program, name);
    if (size === 3) gl.uniform3fv(location, values);
    else gl.uniform4fv(location, values);
  }
  gl.uniform1f(uniforms.lightDistance, 4);
  gl.uniform1f(uniforms.exposure, state.exposure);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  // Where the material and the panel are, in CSS pixels (left, top, right, bottom): for tests.
  const box = panel.getBoundingClientRect();
  view.dataset.material = [origin[0], height - origin[1] - h * zoom, origin[0] + w * zoom, height - origin[1]]
    .map((v) => Math.round(v / dpr)).join(',');
  view.dataset.panel = state.ui ? [box.left, box.top, box.right, box.bottom].map(Math.round).join(',') : '';
  view.dataset.size = [view.clientWidth, view.clientHeight].join(',');
  view.dataset.sphereWindow = [sample.x, sample.y, sample.width, sample.height].join(',');  // what the sphere wraps
  const error = gl.getError();
  if (error !== gl.NO_ERROR) console.error('WebGL error ' + error + ' while drawing');
  updatePanel();
  drawDisk();
  writeHash();
}
