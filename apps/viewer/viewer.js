// The page of `ladarsim view`: one frame at a time of a rendered run, with its ground truth,
// detections (when detect/eval ran) and range image. Frames load on demand as binary PCD.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const SOURCE_VOLUME = 1, SOURCE_FALSE_ALARM = 2;
/// Classes that are the scene's background (the initial map holds them): coloured by range.
const BACKGROUND_CLASSES = new Set(['background', 'terrain', 'building', 'tree']);

async function json(path) {
  const r = await fetch(path);
  return r.ok ? r.json() : null;
}

/// The jet colour map of the paper's figures, t in [0, 1].
function jet(t) {
  const c = (x) => Math.max(0, Math.min(1, x));
  return [c(1.5 - Math.abs(4 * t - 3)), c(1.5 - Math.abs(4 * t - 2)), c(1.5 - Math.abs(4 * t - 1))];
}

/// A frame's binary PCD (as `render` writes it): the fields the viewer draws.
function parsePcd(buffer) {
  const bytes = new Uint8Array(buffer);
  let end = 0, header = '';
  for (;;) {  // header lines up to and including DATA
    const next = bytes.indexOf(10, end);
    const line = new TextDecoder().decode(bytes.subarray(end, next));
    header += line + '\n';
    end = next + 1;
    if (line.startsWith('DATA')) break;
  }
  const get = (key) => header.match(new RegExp('^' + key + ' (.*)$', 'm'))[1].trim().split(/\s+/);
  const fields = get('FIELDS'), sizes = get('SIZE').map(Number), types = get('TYPE'), counts = get('COUNT').map(Number);
  const n = Number(get('POINTS')[0]);
  const offset = {};
  let step = 0;
  fields.forEach((f, i) => { offset[f] = { at: step, size: sizes[i], type: types[i] }; step += sizes[i] * counts[i]; });
  const view = new DataView(buffer, end);
  const read = (f, i) => {
    const o = offset[f], at = i * step + o.at;
    if (o.type === 'F') return o.size === 8 ? view.getFloat64(at, true) : view.getFloat32(at, true);
    return o.size === 4 ? view.getUint32(at, true) : o.size === 2 ? view.getUint16(at, true) : view.getUint8(at);
  };
  const p = { n, xyz: new Float32Array(3 * n), range: new Float32Array(n), object: new Uint32Array(n), source: new Uint8Array(n) };
  for (let i = 0; i < n; ++i) {
    p.xyz[3 * i] = read('x', i); p.xyz[3 * i + 1] = read('y', i); p.xyz[3 * i + 2] = read('z', i);
    p.range[i] = read('range_m', i); p.object[i] = read('object_id', i); p.source[i] = read('source', i);
  }
  return p;
}

function boxLines(box, colour) {
  const geometry = new THREE.EdgesGeometry(new THREE.BoxGeometry(...box.size_m));
  const lines = new THREE.LineSegments(geometry, new THREE.LineBasicMaterial({ color: colour }));
  lines.position.set(...box.centre_m);
  if (box.orientation_wxyz) {
    const [w, x, y, z] = box.orientation_wxyz;
    lines.quaternion.set(x, y, z, w);
  }
  return lines;
}

/// Direction of raster angles (az, el) under the gimbal pointing (gaz, gel), in the sensor frame:
/// Rz(gaz) Ry(-gel) applied to the beam (cos el cos az, cos el sin az, sin el).
function rasterDirection(gaz, gel, az, el) {
  const x0 = Math.cos(el) * Math.cos(az), y0 = Math.cos(el) * Math.sin(az), z0 = Math.sin(el);
  const x1 = x0 * Math.cos(gel) - z0 * Math.sin(gel), z1 = x0 * Math.sin(gel) + z0 * Math.cos(gel);
  return new THREE.Vector3(x1 * Math.cos(gaz) - y0 * Math.sin(gaz), x1 * Math.sin(gaz) + y0 * Math.cos(gaz), z1);
}

async function main() {
  const manifest = await json('/run/manifest.json');
  const truth = (await json('/run/ground_truth.json')) || { frames: [] };
  const files = (await json('/files')) || [];
  const detectionFile = files.find((f) => f.startsWith('detections-') && f.endsWith('.json'));
  const evalFile = files.find((f) => f.startsWith('eval-') && f.endsWith('.json'));
  const detections = detectionFile ? await json('/run/' + detectionFile) : null;
  const scores = evalFile ? await json('/run/' + evalFile) : null;
  const frames = manifest.frames;
  // The target: the one scored, else the cue. A run with neither has none (id 0 is the background
  // map, never a target).
  const target = detections?.target ?? scores?.target ?? (manifest.mount?.cue_object || null);
  document.getElementById('title').textContent = `${manifest.scenario_file ?? 'recorded run'} — ${frames.length} frames`;

  const host = document.getElementById('scene');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  host.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x111111);
  const camera = new THREE.PerspectiveCamera(45, 1, 0.05, 20000);
  camera.up.set(0, 0, 1);  // the sensor frame: x forward, y left, z up
  camera.position.set(-10, 0, 5);
  const controls = new OrbitControls(camera, renderer.domElement);
  const resize = () => {
    const w = host.clientWidth, h = host.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  };
  window.addEventListener('resize', resize);
  resize();
  let layer = new THREE.Group();
  scene.add(layer);

  const slider = document.getElementById('slider');
  slider.max = String(frames.length - 1);
  const follow = document.getElementById('follow');
  const state = { ready: false };

  async function show(k) {
    const info = frames[k];
    const stem = String(info.index).padStart(6, '0');
    const [pcd, range] = await Promise.all([
      fetch(`/run/frames/${stem}.pcd`).then((r) => r.arrayBuffer()),
      fetch(`/range/${info.index}`).then((r) => (r.ok ? r.arrayBuffer() : null)),
    ]);
    const p = parsePcd(pcd);
    const next = new THREE.Group();
    const objects = truth.frames[k]?.objects ?? [];
    const background = new Set([0, ...objects.filter((o) => BACKGROUND_CLASSES.has(o.class)).map((o) => o.id)]);

    // Points: background by range (jet), target, clutter, false alarms and media by source.
    let lo = Infinity, hi = -Infinity, targetReturns = 0;
    for (let i = 0; i < p.n; ++i) {
      if (background.has(p.object[i]) && p.source[i] === 0) { lo = Math.min(lo, p.range[i]); hi = Math.max(hi, p.range[i]); }
    }
    const colours = new Float32Array(3 * p.n);
    const onTarget = [];
    for (let i = 0; i < p.n; ++i) {
      let c;
      if (p.source[i] === SOURCE_FALSE_ALARM) c = [1, 1, 1];
      else if (p.source[i] === SOURCE_VOLUME) c = [0.55, 0.55, 0.55];
      else if (background.has(p.object[i])) c = jet(hi > lo ? (p.range[i] - lo) / (hi - lo) : 0.5);
      else if (target !== null && p.object[i] === target) { c = [1, 0.25, 1]; ++targetReturns; onTarget.push(i); }
      else c = [0.25, 1, 1];
      colours.set(c, 3 * i);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(p.xyz, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    next.add(new THREE.Points(geometry, new THREE.PointsMaterial({ size: 3, sizeAttenuation: false, vertexColors: true })));
    // The target's points again, larger and drawn last over everything: the detection's and the
    // ground truth's outlines enclose them and would otherwise hide them.
    if (onTarget.length) {
      const xyz = new Float32Array(3 * onTarget.length);
      onTarget.forEach((i, j) => xyz.set(p.xyz.subarray(3 * i, 3 * i + 3), 3 * j));
      const top = new THREE.BufferGeometry();
      top.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
      const points = new THREE.Points(top, new THREE.PointsMaterial({ size: 6, sizeAttenuation: false, color: 0xff40ff, depthTest: false }));
      points.renderOrder = 10;
      next.add(points);
    }

    // Ground truth (red) and detections, in the sensor frame: the box around the points (yellow)
    // and the sensor-aware box (cyan, docs/detection.md).
    let boxes = 0, detectedBoxes = 0, targetBox = null;
    for (const o of objects) {
      if (o.id === target) targetBox = o;
      if (background.has(o.id)) continue;  // terrain and buildings: their boxes would hide the rest
      next.add(boxLines(o.box_sensor, 0xff0000));
      ++boxes;
    }
    const d = detections?.detections?.[k];
    if (d && d.found && d.size_m) {
      next.add(boxLines({ centre_m: d.centre_m, size_m: d.size_m.map((s) => Math.max(s, 0.05)) }, 0xffff00));
      if (d.sensor_box) next.add(boxLines(d.sensor_box, 0x00ffff));
      ++detectedBoxes;
    }

    // The field of view (green): the raster's four corner beams and its far edge.
    const reach = targetBox ? 1.2 * Math.hypot(...targetBox.box_sensor.centre_m) : 300;
    const az = (manifest.sensor.derived.field_az_deg * Math.PI) / 360, el = (manifest.sensor.derived.field_el_deg * Math.PI) / 360;
    const corners = [[az, el], [-az, el], [-az, -el], [az, -el]].map(([a, e]) =>
      rasterDirection(info.gimbal_az_rad ?? 0, info.gimbal_el_rad ?? 0, a, e).multiplyScalar(reach));
    const fov = [];
    for (let i = 0; i < 4; ++i) fov.push(new THREE.Vector3(), corners[i], corners[i], corners[(i + 1) % 4]);
    next.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(fov), new THREE.LineBasicMaterial({ color: 0x00ff00 })));

    scene.remove(layer);
    layer = next;
    scene.add(layer);
    if (follow.checked && targetBox) {
      const c = new THREE.Vector3(...targetBox.box_sensor.centre_m);
      const back = c.clone().normalize().multiplyScalar(-Math.max(6, 12 * Math.max(...targetBox.box_sensor.size_m)));
      controls.target.copy(c);
      camera.position.copy(c).add(back).add(new THREE.Vector3(0, 0, 0.15 * back.length()));
      controls.update();
    }

    // The range image, jet from near to far, black where no return. Recorded frames have none
    // (the importers write point clouds only): say so rather than show an empty box.
    document.getElementById('range-box').hidden = !range;
    document.getElementById('no-range').hidden = !!range;
    state.range_image = range ? state.range_image : null;
    if (range) {
      const [w, h] = new Uint32Array(range, 0, 2);
      const r = new Float32Array(range, 8, w * h);
      const canvas = document.getElementById('range');
      canvas.width = w; canvas.height = h;
      // At least 3 screen pixels a raster line: a 3600 x 16 image at the panel's width would be a
      // strip one pixel high.
      canvas.style.height = `${Math.max(canvas.clientWidth * h / w, 3 * h)}px`;
      state.range_image = { width: w, height: h, shown_height_px: canvas.getBoundingClientRect().height };
      const ctx = canvas.getContext('2d'), img = ctx.createImageData(w, h);
      // Colours spread over the 2nd to 98th percentile: one near target does not flatten the rest.
      const seen = Array.from(r).filter((v) => v > 0).sort((a, b) => a - b);
      const rlo = seen.length ? seen[Math.floor(0.02 * (seen.length - 1))] : 0;
      const rhi = seen.length ? seen[Math.floor(0.98 * (seen.length - 1))] : 1;
      for (let i = 0; i < w * h; ++i) {
        const c = r[i] > 0 ? jet(rhi > rlo ? Math.min(1, Math.max(0, (r[i] - rlo) / (rhi - rlo))) : 0.5) : [0, 0, 0];
        img.data.set([c[0] * 255, c[1] * 255, c[2] * 255, 255], 4 * i);
      }
      ctx.putImageData(img, 0, 0);
    }

    // The panel.
    const perFrame = scores?.per_frame?.[k];
    // Detections without a target id: a recording has no object ids, yet its detections are drawn.
    const targetText = target !== null ? `object ${target}`
      : detections ? `none named (no cue); detection box ${detectedBoxes ? 'drawn' : 'not found'} this frame`
      : 'none (no cue, no detections)';
    const rows = [
      // Counted from 1 like the slider's label: a recording's first frame is index 0.
      ['frame', `${k + 1} of ${frames.length}`],
      // From the run's first frame: a recording's times are seconds since 1970.
      ['time', `${((info.start_time_s ?? 0) - (frames[0].start_time_s ?? 0)).toFixed(3)} s`],
      ['gimbal az / el', `${(((info.gimbal_az_rad ?? 0) * 180) / Math.PI).toFixed(3)} / ${(((info.gimbal_el_rad ?? 0) * 180) / Math.PI).toFixed(3)} deg`],
      ['returns', p.n],
      ['target', targetText],
      ['range to target', targetBox ? `${Math.hypot(...targetBox.box_sensor.centre_m).toFixed(1)} m` : '-'],
      ['target returns', target === null ? '-' : targetReturns],
      ['L2', perFrame?.l2_m != null ? `${perFrame.l2_m.toFixed(3)} m` : '-'],
      ['IoU (sensor-aware box)', perFrame ? perFrame.iou.toFixed(3) : '-'],
      ['IoU bird\'s-eye', perFrame?.iou_bev != null ? perFrame.iou_bev.toFixed(3) : '-'],
    ];
    document.getElementById('panel').innerHTML = rows.map(([a, b]) => `<tr><td>${a}</td><td>${b}</td></tr>`).join('');
    document.getElementById('frame-label').textContent = `${k + 1}/${frames.length}`;
    Object.assign(state, { ready: true, frame: info.index, points: p.n, target, target_returns: targetReturns, boxes, detected_boxes: detectedBoxes });
    document.getElementById('state').textContent = JSON.stringify(state);
  }

  let current = Number(new URLSearchParams(location.search).get('frame') ?? 0);
  current = Math.max(0, Math.min(frames.length - 1, current));
  slider.value = String(current);
  let loading = show(current);
  slider.addEventListener('input', () => { current = Number(slider.value); loading = loading.then(() => show(current)); });
  let timer = null;
  document.getElementById('play').addEventListener('click', (e) => {
    if (timer) { clearInterval(timer); timer = null; e.target.textContent = 'play'; return; }
    e.target.textContent = 'pause';
    timer = setInterval(() => {
      current = (current + 1) % frames.length;
      slider.value = String(current);
      loading = loading.then(() => show(current));
    }, 200);
  });
  window.viewerState = state;
  renderer.setAnimationLoop(() => { controls.update(); renderer.render(scene, camera); });
}

main().catch((e) => {
  document.getElementById('state').textContent = JSON.stringify({ ready: false, error: String(e) });
  document.body.insertAdjacentHTML('afterbegin', `<pre style="color:#f66">${e}</pre>`);
});
