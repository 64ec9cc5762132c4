// The HTML viewer of ashlar.export (web/viewer.html loads it): draws the
// scene the engine wrote into the page (engine/io/viewer_page.cpp) with
// three.js. Turn with the left mouse button, pan with the right one, zoom
// with the wheel; hovering (or tapping) an object shows its name and
// values; the check boxes show and hide each layer. The page of a
// simulation also plays it (play and pause, a time slider, loop): its
// blocks and their outlines move through the key frames the engine wrote,
// playing as the page opens unless the scene says not to; so does the
// collapse mechanism of a still's result. Buttons show the
// structure from the front, the side, the top or obliquely (iso), in
// perspective or orthographic; a planar structure opens in the front view,
// orthographic. A key names the colour of each role drawn (compression,
// tension, friction, interfaces, thrust line or network, ...) and a scale
// bar reads the arrows' length as a force.
// Coordinates are ashlar's: metres, z up.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const scene_data = JSON.parse(document.getElementById("ashlar-scene").textContent);
const view = document.getElementById("view");

function fail(text) {
  const message = document.getElementById("message");
  message.textContent = text;
  message.style.display = "block";
}

function srgb([r, g, b]) {
  return new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace);
}

let renderer;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true });
} catch (error) {
  // The usual cause is WebGL switched off with hardware acceleration, or a
  // headless Chromium without a software GL: it draws WebGL on SwiftShader
  // only with --use-angle=swiftshader --enable-unsafe-swiftshader (the flags
  // tests/tools/check_viewer.js uses); --disable-gpu --use-gl=swiftshader
  // alone leaves it without WebGL.
  fail("This browser cannot draw WebGL, which the viewer needs (" + error.message + "). " +
       "WebGL is usually off because hardware acceleration is: turn it on (Chrome, Edge: Settings > System > " +
       "Use graphics acceleration when available; Firefox: Settings > Performance) or open the page in " +
       "another browser. Headless Chromium draws WebGL only with --use-angle=swiftshader " +
       "--enable-unsafe-swiftshader; --disable-gpu --use-gl=swiftshader alone does not work.");
  throw error;
}
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(srgb([0.957, 0.957, 0.945]));
view.appendChild(renderer.domElement);

const scene = new THREE.Scene();
// Two cameras, one of them in use; the view buttons and the orthographic
// box switch between them.
const perspective = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
const orthographic = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.01, 1000);
for (const c of [perspective, orthographic]) {
  c.up.set(0, 0, 1);
  scene.add(c);
}
let camera = scene_data.planar ? orthographic : perspective;
// A soft light everywhere and one from the eye, so that faces turned to
// the viewer show their colour and the others darken with their angle.
scene.add(new THREE.AmbientLight(0xffffff, 1.4));
const headlight = new THREE.DirectionalLight(0xffffff, 1.8);
headlight.position.set(0.3, 0.5, 1);
camera.add(headlight);
camera.add(headlight.target);

// One group per layer, switched by its check box.
const layers = new Map();
for (const { name } of scene_data.layers) {
  const group = new THREE.Group();
  group.name = name;
  layers.set(name, group);
  scene.add(group);
}

const pickable = [];
const block_materials = [];
const equilibrium_materials = [];
const meshes = [];
// A force arrow from what the scene holds of it: tail and tip (m), the
// shaft's and the head's radius, the head's length (m), and the sides of
// its prism and pyramid; the solid of the engine's arrow_faces, turned
// about its axis.
function arrow_geometry([tx, ty, tz, px, py, pz, shaft, head, head_length, sides]) {
  const axis = new THREE.Vector3(px - tx, py - ty, pz - tz);
  const length = axis.length();
  const neck = length - head_length;
  const profile = [[0, 0], [shaft, 0], [shaft, neck], [head, neck], [0, length]].map(([x, y]) => new THREE.Vector2(x, y));
  const geometry = new THREE.LatheGeometry(profile, sides).toNonIndexed();
  geometry.applyQuaternion(new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis.normalize()));
  geometry.translate(tx, ty, tz);
  return geometry;
}

// The tubes of a thrust network from what the scene holds of them: per
// tube its ends (m) and radius (m); open prisms of six sides, as the
// engine's tube_faces draws them (their ends meet inside blocks and joints).
function tube_geometry(tubes) {
  const sides = 6;
  const positions = [];
  const axis = new THREE.Vector3(), first = new THREE.Vector3(), second = new THREE.Vector3();
  const from = new THREE.Vector3(), to = new THREE.Vector3(), offset = new THREE.Vector3();
  const ring = (center, j, radius) => {
    const angle = (2 * Math.PI * j) / sides;
    offset.copy(first).multiplyScalar(Math.cos(angle)).addScaledVector(second, Math.sin(angle)).multiplyScalar(radius);
    return center.clone().add(offset).toArray();
  };
  for (let k = 0; k + 7 <= tubes.length; k += 7) {
    from.fromArray(tubes, k);
    to.fromArray(tubes, k + 3);
    const radius = tubes[k + 6];
    axis.subVectors(to, from);
    if (axis.length() <= 1e-3 * radius) continue;
    axis.normalize();
    // Perpendicular to the axis, from the coordinate axis least aligned with it.
    const least = [Math.abs(axis.x), Math.abs(axis.y), Math.abs(axis.z)].reduce((m, v, i, a) => (v < a[m] ? i : m), 0);
    first.crossVectors(axis, new THREE.Vector3().setComponent(least, 1)).normalize();
    second.crossVectors(axis, first);
    for (let j = 0; j < sides; ++j) {
      const a = ring(from, j, radius), b = ring(from, j + 1, radius), c = ring(to, j + 1, radius), d = ring(to, j, radius);
      positions.push(...a, ...b, ...c, ...a, ...c, ...d);
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
  return geometry;
}

for (const object of scene_data.objects) {
  let geometry;
  if (object.arrow) {
    geometry = arrow_geometry(object.arrow);
  } else if (object.tubes) {
    geometry = tube_geometry(object.tubes);
  } else {
    geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.Float32BufferAttribute(object.positions, 3));
    geometry.setIndex(object.triangles);
  }
  // Every polygon has its own vertices, so vertex normals are face normals.
  geometry.computeVertexNormals();
  const [r, g, b, a] = object.color;
  const material = new THREE.MeshLambertMaterial({
    color: srgb([r, g, b]),
    // Arrows and tubes are drawn from both sides, whichever way they wind.
    side: object.two_sided || object.arrow || object.tubes ? THREE.DoubleSide : THREE.FrontSide,
  });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.name = object.name;
  mesh.userData = { layer: object.layer, info: object.info };
  material.userData.alpha = a;
  if (object.layer === "interfaces") {
    // Drawn over the block faces they lie on.
    material.polygonOffset = true;
    material.polygonOffsetFactor = -1;
    material.polygonOffsetUnits = -4;
  }
  if (["forces", "thrust", "interfaces"].includes(object.layer)) equilibrium_materials.push(material);
  if (object.layer === "blocks") {
    block_materials.push(material);
  } else {
    set_opacity(material, a);
  }
  layers.get(object.layer).add(mesh);
  pickable.push(mesh);
  meshes.push(mesh);
}

function set_opacity(material, opacity) {
  material.opacity = opacity;
  material.transparent = opacity < 1;
  // Translucent blocks must not hide what runs inside them.
  material.depthWrite = opacity >= 1;
  material.needsUpdate = true;
}

function set_block_opacity(opacity) {
  for (const material of block_materials) set_opacity(material, opacity * material.userData.alpha);
}

// The outlines: one set of lines for what stands still, and one per block
// that moves, which moves with it.
const outline_material = new THREE.LineBasicMaterial({ color: srgb(scene_data.edge_color) });
function outline_lines(points) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(points, 3));
  const lines = new THREE.LineSegments(geometry, outline_material);
  layers.get("edges").add(lines);
  return lines;
}
const animation = scene_data.animation;
// Per moving block: what moves (its mesh and its outline) and its track.
const bodies = [];
if (animation) {
  const moving = new Uint8Array(scene_data.outline.length / 3);
  for (const track of animation.tracks) {
    const [first, last] = track.outline;
    moving.fill(1, first, last);
    const [cx, cy, cz] = track.centroid;
    // Its objects (the block, the limit markers it carries) and its outline
    // are drawn about the centroid, then placed by the pose.
    const parts = track.objects.map((k) => meshes[k]);
    if (last > first) parts.push(outline_lines(scene_data.outline.slice(3 * first, 3 * last)));
    for (const part of parts) part.geometry.translate(-cx, -cy, -cz);
    bodies.push({ parts, track });
  }
  const still = scene_data.outline.filter((value, k) => !moving[Math.floor(k / 3)]);
  if (still.length > 0) outline_lines(still);
} else if (scene_data.outline.length > 0) {
  outline_lines(scene_data.outline);
}

// Places every moving block at time t (s): between the key frames around
// it, positions linear and rotations by slerp, as glTF viewers do.
const pose = { position: new THREE.Vector3(), next: new THREE.Vector3(), rotation: [0, 0, 0, 1] };
function show_time(t) {
  const times = animation.times;
  let k = 0;
  let hi = times.length - 1;
  while (k < hi - 1) {
    const mid = (k + hi) >> 1;
    if (times[mid] <= t) k = mid;
    else hi = mid;
  }
  const next = Math.min(k + 1, times.length - 1);
  const f = next > k ? Math.min(Math.max((t - times[k]) / (times[next] - times[k]), 0), 1) : 0;
  if (animation.mechanism > 0) {
    // The forces and the thrust are the equilibrium of the blocks as they
    // stand: they fade as the mechanism moves the blocks away.
    const shown = 1 - 0.8 * Math.min(Math.max(1 - Math.abs(t - 1), 0), 1);
    for (const material of equilibrium_materials) set_opacity(material, shown * material.userData.alpha);
  }
  for (const { parts, track } of bodies) {
    const p = track.positions;
    pose.position.set(p[3 * k], p[3 * k + 1], p[3 * k + 2]);
    pose.position.lerp(pose.next.set(p[3 * next], p[3 * next + 1], p[3 * next + 2]), f);
    THREE.Quaternion.slerpFlat(pose.rotation, 0, track.rotations, 4 * k, track.rotations, 4 * next, f);
    for (const part of parts) {
      part.position.copy(pose.position);
      part.quaternion.fromArray(pose.rotation);
    }
  }
}
if (animation) show_time(animation.times[0]);

// Controls: one check box per layer, the blocks' opacity, the view reset.
const layer_boxes = document.getElementById("layers");
for (const { name, visible } of scene_data.layers) {
  const label = document.createElement("label");
  const box = document.createElement("input");
  box.type = "checkbox";
  box.id = "layer-" + name;
  box.checked = visible;
  layers.get(name).visible = visible;
  box.addEventListener("change", () => {
    layers.get(name).visible = box.checked;
    hover(null);
    request_render();
  });
  label.append(box, " " + name);
  layer_boxes.append(label);
}
const opacity_input = document.getElementById("opacity");
opacity_input.value = scene_data.opacity;
set_block_opacity(scene_data.opacity);
opacity_input.addEventListener("input", () => {
  set_block_opacity(Number(opacity_input.value));
  request_render();
});

document.title = scene_data.title;
document.getElementById("title").textContent = scene_data.title;
document.getElementById("summary").textContent = scene_data.summary;

if (scene_data.legend) {
  const { label, lo, hi, stops } = scene_data.legend;
  const css = stops.map(([r, g, b], k) =>
    `rgb(${Math.round(255 * r)}, ${Math.round(255 * g)}, ${Math.round(255 * b)}) ${(100 * k) / (stops.length - 1)}%`);
  document.getElementById("legend-bar").style.background = `linear-gradient(to right, ${css.join(", ")})`;
  document.getElementById("legend-label").textContent = label;
  document.getElementById("legend-lo").textContent = lo;
  document.getElementById("legend-hi").textContent = hi;
  document.getElementById("legend").classList.remove("hidden");
}

// The key: the colour of each role drawn.
if (scene_data.key && scene_data.key.length > 0) {
  const key = document.getElementById("key");
  for (const { label, color } of scene_data.key) {
    const row = document.createElement("div");
    row.className = "row";
    const swatch = document.createElement("span");
    swatch.className = "swatch";
    swatch.style.background = "#" + srgb(color).getHexString(THREE.SRGBColorSpace);
    row.append(swatch, label);
    key.append(row);
  }
  key.classList.remove("hidden");
}

// A force in N, kN or MN, as the engine writes them.
function force_text(newtons) {
  const [unit, size] = newtons >= 1e6 ? ["MN", 1e6] : newtons >= 1e3 ? ["kN", 1e3] : ["N", 1];
  return `${Number((newtons / size).toPrecision(4))} ${unit}`;
}

// The largest of 1, 2 and 5 x 10^k not above value (> 0).
function round_down(value) {
  const decade = Math.pow(10, Math.floor(Math.log10(value)));
  const step = [5, 2, 1].find((s) => s * decade <= value * (1 + 1e-12)) || 1;
  return Number((step * decade).toPrecision(6));
}

// The scale bar: a round force whose arrow is at most 120 pixels long at
// the distance of the point the view turns about.
const metres_per_newton = scene_data.force_scale;
const scale_rule = document.getElementById("scale-rule");
const scale_text = document.getElementById("scale-text");
if (metres_per_newton > 0) {
  document.getElementById("scale-note").textContent =
    `1 m of arrow = ${force_text(1 / metres_per_newton)}`;
  document.getElementById("scale").classList.remove("hidden");
}
function update_scale() {
  if (!(metres_per_newton > 0)) return;
  const height = renderer.domElement.clientHeight;
  const span = camera === orthographic
    ? (orthographic.top - orthographic.bottom) / orthographic.zoom
    : 2 * camera.position.distanceTo(controls.target) * Math.tan(THREE.MathUtils.degToRad(perspective.fov / 2));
  const pixels_per_newton = (height / span) * metres_per_newton;
  const newtons = round_down(120 / pixels_per_newton);
  scale_rule.style.width = `${Math.round(newtons * pixels_per_newton)}px`;
  scale_text.textContent = force_text(newtons) + (camera === perspective ? " (at the centre of the view)" : "");
}
// The views: where the eye is seen from the structure (z up). The opening
// view is "front" for a planar structure (x-z plane), else "oblique": from
// the front, a little from the right and from above.
const views = {
  front: new THREE.Vector3(0, -1, 0),
  side: new THREE.Vector3(1, 0, 0),
  top: new THREE.Vector3(0, -1e-4, 1),  // y up on the screen
  iso: new THREE.Vector3(1, -1, 1),
  oblique: new THREE.Vector3(0.35, -1, 0.45),
};
const opening_view = scene_data.planar ? "front" : "oblique";
const bounds = new THREE.Box3();
for (const group of layers.values()) bounds.expandByObject(group);
const controls = new OrbitControls(camera, renderer.domElement);
// The orthographic camera's half height at zoom 1 (m).
let ortho_half = 1;
// The view last fitted, while the user has not turned, panned or zoomed
// since: a resized window fits it again.
let fitted = null;
controls.addEventListener("start", () => { fitted = null; });

function use_camera(next) {
  camera = next;
  camera.add(headlight);
  camera.add(headlight.target);
  controls.object = camera;
  document.body.dataset.projection = camera === orthographic ? "orthographic" : "perspective";
  document.getElementById("orthographic").checked = camera === orthographic;
}

function update_projection() {
  const aspect = perspective.aspect;
  orthographic.left = -ortho_half * aspect;
  orthographic.right = ortho_half * aspect;
  orthographic.top = ortho_half;
  orthographic.bottom = -ortho_half;
  perspective.updateProjectionMatrix();
  orthographic.updateProjectionMatrix();
}

// Looks at the whole structure from `name`'s direction, as close as keeps
// every corner of its bounding box in view.
function fit_view(name) {
  const center = bounds.getCenter(new THREE.Vector3());
  const back = views[name].clone().normalize();  // from the structure to the eye
  const right = new THREE.Vector3().crossVectors(camera.up, back).normalize();
  const up = new THREE.Vector3().crossVectors(back, right);
  const tan_v = Math.tan(THREE.MathUtils.degToRad(perspective.fov / 2));
  const tan_h = tan_v * perspective.aspect;
  let distance = 0, half_width = 0, half_height = 0, depth = 0;
  for (let corner = 0; corner < 8; ++corner) {
    const p = new THREE.Vector3(corner & 1 ? bounds.max.x : bounds.min.x, corner & 2 ? bounds.max.y : bounds.min.y,
                                corner & 4 ? bounds.max.z : bounds.min.z).sub(center);
    const toward = p.dot(back);
    distance = Math.max(distance, toward + Math.abs(p.dot(right)) / tan_h, toward + Math.abs(p.dot(up)) / tan_v);
    half_width = Math.max(half_width, Math.abs(p.dot(right)));
    half_height = Math.max(half_height, Math.abs(p.dot(up)));
    depth = Math.max(depth, Math.abs(toward));
  }
  if (camera === orthographic) {
    ortho_half = 1.1 * Math.max(half_height, half_width / perspective.aspect, 1e-6);
    orthographic.zoom = 1;
    distance = 2 * depth + ortho_half;  // the eye outside the box
  } else {
    distance *= 1.25;  // a margin, which also keeps most structures clear of the panels
  }
  camera.position.copy(center).addScaledVector(back, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  update_projection();
  controls.target.copy(center);
  controls.update();
  document.body.dataset.view = name;
  fitted = name;
}

// Switches between perspective and orthographic, keeping the direction,
// the point turned about and the size of what is there on the screen.
function set_orthographic(on) {
  if ((camera === orthographic) === on) return;
  const target = controls.target;
  const offset = camera.position.clone().sub(target);
  const tan_v = Math.tan(THREE.MathUtils.degToRad(perspective.fov / 2));
  let distance = offset.length();
  if (on) {
    ortho_half = distance * tan_v;
    orthographic.zoom = 1;
  } else {
    distance = ortho_half / orthographic.zoom / tan_v;
  }
  const next = on ? orthographic : perspective;
  next.position.copy(target).addScaledVector(offset.normalize(), distance);
  next.near = distance / 100;
  next.far = distance * 10;
  use_camera(next);
  update_projection();
  controls.update();
  fitted = null;
}

function reset_view() {
  fit_view(opening_view);
}
document.getElementById("reset").addEventListener("click", () => {
  reset_view();
  request_render();
});
for (const button of document.querySelectorAll("#views button")) {
  button.addEventListener("click", () => {
    fit_view(button.dataset.view);
    request_render();
  });
}
document.getElementById("orthographic").addEventListener("change", (event) => {
  set_orthographic(event.target.checked);
  request_render();
});
use_camera(camera);

// Hover: the object under the pointer, among the visible ones. Blocks that
// are translucent give way to what lies inside them (arrows, the thrust
// line, interfaces).
const raycaster = new THREE.Raycaster();
const pointer = new THREE.Vector2();
let hovered = null;
const info = document.getElementById("info");
const info_hint = info.innerHTML;

function visible_in_scene(object) {
  for (let o = object; o; o = o.parent) if (!o.visible) return false;
  return true;
}

function hover(mesh) {
  if (mesh === hovered) return;
  if (hovered) hovered.material.emissive.setRGB(0, 0, 0);
  hovered = mesh;
  if (!mesh) {
    info.innerHTML = info_hint;
    return;
  }
  mesh.material.emissive.setRGB(0.25, 0.25, 0.25);
  const heading = document.createElement("h2");
  heading.textContent = mesh.name;
  const table = document.createElement("table");
  for (const [key, value] of mesh.userData.info) {
    const row = table.insertRow();
    row.insertCell().textContent = key;
    row.insertCell().textContent = value;
  }
  info.replaceChildren(heading, table);
}

// Hover with a mouse; a tap (touch screens have no hover) picks too.
function pick(event) {
  const rect = renderer.domElement.getBoundingClientRect();
  pointer.set(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  const hits = raycaster.intersectObjects(pickable.filter(visible_in_scene), false);
  const see_through = (hit) => hit.object.userData.layer === "blocks" && hit.object.material.transparent;
  const chosen = hits.find((hit) => !see_through(hit)) || hits[0];
  hover(chosen ? chosen.object : null);
  request_render();
}
renderer.domElement.addEventListener("pointermove", pick);
renderer.domElement.addEventListener("click", pick);
renderer.domElement.addEventListener("pointerleave", () => {
  hover(null);
  request_render();
});

// Drawn only when something changed.
let render_requested = false;
function request_render() {
  if (render_requested) return;
  render_requested = true;
  requestAnimationFrame(() => {
    render_requested = false;
    update_scale();
    renderer.render(scene, camera);
  });
}
controls.addEventListener("change", request_render);

function resize() {
  const width = view.clientWidth, height = view.clientHeight;
  renderer.setSize(width, height);
  perspective.aspect = width / height;
  update_projection();
  if (fitted) fit_view(fitted);
  request_render();
}
window.addEventListener("resize", resize);
resize();
reset_view();

// The player: play and pause, the time slider, loop. Simulated time runs at
// the wall clock's pace. A mechanism's page plays rest, the mechanism at its
// extreme, rest, over 2 s, opening at the extreme; its read-out is the
// fastest centroid's displacement (the summary says so), and the forces and
// thrust fade as the blocks leave where they stand.
if (animation) {
  const times = animation.times;
  const start = times[0], end = times[times.length - 1];
  const play_button = document.getElementById("play");
  const slider = document.getElementById("time");
  const time_text = document.getElementById("time-text");
  const loop = document.getElementById("loop");
  const digits = end - start < 1 ? 3 : 2;
  slider.min = start;
  slider.max = end;
  let time = start;
  let playing = false;
  let last_frame = 0;

  const reach = animation.mechanism;
  const set_time = (t) => {
    time = Math.min(Math.max(t, start), end);
    slider.value = time;
    time_text.textContent = reach > 0
      ? `mechanism ${Number((reach * (1 - Math.abs(time - 1))).toPrecision(3))} m / ${Number(reach.toPrecision(4))} m`
      : `${time.toFixed(digits)} s / ${end.toFixed(digits)} s`;
    show_time(time);
    request_render();
  };
  const set_playing = (on) => {
    playing = on;
    play_button.textContent = on ? "pause" : "play";
    if (on) {
      last_frame = performance.now();
      requestAnimationFrame(advance);
    }
  };
  function advance(now) {
    if (!playing) return;
    let t = time + Math.max(now - last_frame, 0) / 1000;
    last_frame = now;
    if (t >= end) {
      if (loop.checked && end > start) {
        t = start + ((t - start) % (end - start));
      } else {
        set_time(end);
        set_playing(false);
        return;
      }
    }
    set_time(t);
    requestAnimationFrame(advance);
  }
  play_button.addEventListener("click", () => {
    if (!playing && time >= end) set_time(start);
    set_playing(!playing);
  });
  slider.addEventListener("input", () => set_time(Number(slider.value)));
  set_time(animation.start ?? start);
  document.getElementById("player").classList.remove("hidden");
  if (animation.autoplay !== false) set_playing(true);
}
