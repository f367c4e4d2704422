// report.html's script: draws what ramap put in the page's data (html_report.h says what that
// holds). Plain browser JavaScript and the inlined three.js (global THREE): no module, no network,
// so the page opens from file://. window.ramapReport lets the browser test see what was drawn.
(function() {
'use strict';

const data = JSON.parse(document.getElementById('ramap-data').textContent);
const PALETTE = [
  '#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22',
  '#7f7f7f'
];
const REFERENCE_COLOR = '#b8bec8';
const report = {
  ready: false,
  webgl: null,
  view: null
};
window.ramapReport = report;

// ---------------------------------------------------------------- small helpers
function element(tag, attributes, children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes || {})) {
    if (key === 'text')
      node.textContent = value;
    else if (key === 'html')
      node.innerHTML = value;
    else
      node.setAttribute(key, value);
  }
  for (const child of children || []) node.append(child);
  return node;
}

function svg(tag, attributes, text) {
  const node = document.createElementNS('http://www.w3.org/2000/svg', tag);
  for (const [key, value] of Object.entries(attributes || {})) node.setAttribute(key, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

function fixed(value, digits) {
  return value === null || value === undefined || !isFinite(value) ? '-' :
                                                                     Number(value).toFixed(digits);
}

// The least and greatest of `values` and `extra`, by a loop: spreading a long array into
// Math.min overflows the call stack (past about 125000 values).
function minimum(values, extra) {
  let least = extra;
  for (const v of values)
    if (v < least) least = v;
  return least;
}
function maximum(values, extra) {
  let greatest = extra;
  for (const v of values)
    if (v > greatest) greatest = v;
  return greatest;
}

function quantile(values, q) {
  const sorted = values.filter((v) => v !== null && isFinite(v)).sort((a, b) => a - b);
  if (sorted.length === 0) return null;
  return sorted[Math.min(sorted.length - 1, Math.floor(q * (sorted.length - 1) + 0.5))];
}

// Green (low) through yellow to red (high), t in [0, 1].
function ramp(t) {
  const stops = [[0x1a, 0x98, 0x50], [0xfe, 0xe0, 0x8b], [0xd7, 0x30, 0x27]];
  const x = Math.max(0, Math.min(1, t)) * (stops.length - 1);
  const k = Math.min(stops.length - 2, Math.floor(x));
  const f = x - k;
  return stops[k].map((c, i) => (c + f * (stops[k + 1][i] - c)) / 255);
}

function hexToRgb(hex) {
  const n = parseInt(hex.slice(1), 16);
  return [((n >> 16) & 255) / 255, ((n >> 8) & 255) / 255, (n & 255) / 255];
}

const models = (data.models ||
                []).map((model, k) => Object.assign(model, {color: PALETTE[k % PALETTE.length]}));
const reference = data.reference || null;

// ---------------------------------------------------------------- header and tables
function renderHeader() {
  document.getElementById('title').textContent = data.title || 'ramap report';
  document.getElementById('subtitle').textContent = data.subtitle || '';
  document.getElementById('footer').textContent = 'Written by ' + (data.written_by || 'ramap') +
      '. One self-contained file: it needs no network and no server.';
}

function table(columns, rows) {
  const head = element('tr', {}, columns.map((c) => element('th', {text: c})));
  const body = rows.map(
      (row) => element('tr', {}, row.map((cell) => {
        if (cell instanceof Node) return element('td', {}, [cell]);
        return element('td', {text: cell === null || cell === undefined ? '' : String(cell)});
      })));
  return element('table', {}, [element('thead', {}, [head]), element('tbody', {}, body)]);
}

function renderComparison(section) {
  const comparison = data.comparison;
  if (!comparison) return;
  section.append(element('h2', {text: 'Mappers on the same database'}));
  section.append(element(
      'p', {text: comparison.num_images + ' images; reference: ' + comparison.reference + '.'}));
  const glomap = comparison.runs.some((run) => run.name === 'GLOMAP');
  const columns = [
    'mapper', 'registered', 'AUC@1', 'AUC@3', 'AUC@5', 'AUC@10', 'rot. err. median (deg)',
    'ATE RMSE', 'ATE / extent', 'seconds', 'speed-up over COLMAP'
  ];
  if (glomap) columns.push('speed-up over GLOMAP');
  const rows = comparison.runs.map((run) => {
    const e = run.evaluation;
    const auc = (k) =>
        (e && e.relative && e.relative.auc_by_threshold_deg ?
             fixed(100 * e.relative.auc_by_threshold_deg[k], 1) :
             '-');
    const row = [
      element(
          'span', {},
          [element('span', {class: 'swatch', style: 'background:' + colorOf(run.name)}), run.name]),
      run.succeeded ? run.num_registered + ' / ' + comparison.num_images : 'failed',
      e ? auc('1') : (isReference(run) ? '(ref.)' : '-'), e ? auc('3') : '', e ? auc('5') : '',
      e ? auc('10') : '', e && e.rotation_error_deg ? fixed(e.rotation_error_deg.median, 3) : '',
      e && e.ate ? fixed(e.ate.rmse, 4) : '',
      e && e.ate ? fixed(100 * e.ate.rmse_over_extent, 2) + '%' : '', fixed(run.seconds, 2),
      run.speedup_over_colmap ? fixed(run.speedup_over_colmap, 1) + 'x' : '-'
    ];
    if (glomap) row.push(run.speedup_over_glomap ? fixed(run.speedup_over_glomap, 1) + 'x' : '-');
    return row;
  });
  section.append(table(columns, rows));
  section.append(element('p', {
    class: 'hint',
    text:
        'AUC in %, over every image pair (an unregistered image makes its pairs failures); rotation error after the similarity alignment of the camera centres; each mapper timed as a whole process.'
  }));
  const commands = element('details', {}, [element('summary', {text: 'Commands that were run'})]);
  commands.append(element(
      'pre', {text: comparison.runs.map((run) => run.name + ':\n  ' + run.command).join('\n')}));
  section.append(commands);
}

// COLMAP's run is the reference of a comparison without ground truth.
function isReference(run) {
  return run.succeeded && run.name === 'COLMAP' && !data.reference;
}

function colorOf(name) {
  const model = models.find((m) => m.name === name);
  return model ? model.color : REFERENCE_COLOR;
}

// ---------------------------------------------------------------- 3D view
function centerOf(images, k) {
  return [images.center[3 * k], images.center[3 * k + 1], images.center[3 * k + 2]];
}

// Where the view looks, how large the scene is, which way is up (the cameras' mean "up", -y).
function sceneFrame() {
  const sets = reference ? [reference] : [];
  sets.push(...models);
  const centers = [];
  const ups = [0, 0, 0];
  for (const set of sets) {
    const images = set.images;
    for (let k = 0; k < images.name.length; ++k) {
      const c = centerOf(images, k);
      if (c.every(isFinite)) centers.push(c);
      const q = new THREE.Quaternion(
          images.rotation[4 * k], images.rotation[4 * k + 1], images.rotation[4 * k + 2],
          images.rotation[4 * k + 3]);
      const up = new THREE.Vector3(0, -1, 0).applyQuaternion(q);
      ups[0] += up.x;
      ups[1] += up.y;
      ups[2] += up.z;
    }
  }
  const median = [0, 1, 2].map((i) => quantile(centers.map((c) => c[i]), 0.5) || 0);
  const distances =
      centers.map((c) => Math.hypot(c[0] - median[0], c[1] - median[1], c[2] - median[2]));
  const radius = Math.max(quantile(distances, 0.9) || 1, 1e-6);
  const up = new THREE.Vector3(ups[0], ups[1], ups[2]);
  if (up.length() < 1e-9) up.set(0, 0, 1);
  return {center: new THREE.Vector3(...median), radius, up: up.normalize()};
}

function frustumSize(set, radius) {
  let size = (set.sequence ? 0.04 : 0.08) * radius;
  if (set.sequence && set.images.name.length > 2) {
    const steps = [];
    for (let k = 1; k < set.images.name.length; ++k) {
      const a = centerOf(set.images, k - 1);
      const b = centerOf(set.images, k);
      steps.push(Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
    const step = quantile(steps, 0.5);
    if (step > 0) size = Math.min(size, 1.5 * step);
  }
  return size;
}

// One line-segment geometry holding every camera's frustum: apex to the four image corners and
// the image rectangle, 16 vertices a camera.
function frustaGeometry(images, size) {
  const count = images.name.length;
  const positions = new Float32Array(count * 16 * 3);
  const q = new THREE.Quaternion();
  const corner = new THREE.Vector3();
  let p = 0;
  for (let k = 0; k < count; ++k) {
    const c = centerOf(images, k);
    q.set(
        images.rotation[4 * k], images.rotation[4 * k + 1], images.rotation[4 * k + 2],
        images.rotation[4 * k + 3]);
    const tx = images.half_fov[2 * k];
    const ty = images.half_fov[2 * k + 1];
    const corners = [[-tx, -ty], [tx, -ty], [tx, ty], [-tx, ty]].map(([x, y]) => {
      corner.set(x * size, y * size, size).applyQuaternion(q);
      return [c[0] + corner.x, c[1] + corner.y, c[2] + corner.z];
    });
    const segments = [];
    for (let i = 0; i < 4; ++i) segments.push(c, corners[i]);
    for (let i = 0; i < 4; ++i) segments.push(corners[i], corners[(i + 1) % 4]);
    for (const v of segments) {
      positions[p++] = v[0];
      positions[p++] = v[1];
      positions[p++] = v[2];
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute(
      'color', new THREE.Float32BufferAttribute(new Float32Array(count * 16 * 3), 3));
  return geometry;
}

function pointsObject(points, frame) {
  if (!points || !points.count) return null;
  const positions = new Float32Array(points.xyz);
  const colors = new Float32Array(points.count * 3);
  if (points.rgb) {
    for (let k = 0; k < colors.length; ++k) colors[k] = points.rgb[k] / 255;
  } else {
    // No image colours: shade by height along the scene's up direction.
    const heights = [];
    for (let k = 0; k < points.count; ++k) {
      heights.push(
          positions[3 * k] * frame.up.x + positions[3 * k + 1] * frame.up.y +
          positions[3 * k + 2] * frame.up.z);
    }
    const low = quantile(heights, 0.02);
    const high = quantile(heights, 0.98);
    for (let k = 0; k < points.count; ++k) {
      const t = high > low ? (heights[k] - low) / (high - low) : 0.5;
      colors[3 * k] = 0.22 + 0.2 * t;
      colors[3 * k + 1] = 0.32 + 0.25 * t;
      colors[3 * k + 2] = 0.48 + 0.25 * t;
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.Float32BufferAttribute(colors, 3));
  return new THREE.Points(
      geometry, new THREE.PointsMaterial({size: 2, sizeAttenuation: false, vertexColors: true}));
}

function trajectoryObject(images, color) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute(
      'position', new THREE.Float32BufferAttribute(new Float32Array(images.center), 3));
  return new THREE.Line(geometry, new THREE.LineBasicMaterial({color}));
}

const METRICS = [
  {key: 'rotation_error_deg', label: 'rotation error (deg)'},
  {key: 'position_error', label: 'position error'},
  {key: 'reprojection_error_px', label: 'mean reprojection error (px)'},
  {key: 'model', label: 'one colour per model'},
];

// The colourings some model has a value for (a model without points has no reprojection error).
function availableMetrics() {
  return METRICS.filter(
      (metric) => metric.key === 'model' ||
          models.some(
              (m) => Array.isArray(m.images[metric.key]) &&
                  m.images[metric.key].some((v) => v !== null)));
}

function buildView() {
  const container = document.getElementById('view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (error) {
    container.append(element('p', {
      class: 'message',
      text:
          'This browser gives the page no WebGL context, so the 3D view is off; the tables and plots below are complete.'
    }));
    return null;
  }
  const gl = renderer.getContext();
  report.webgl =
      typeof WebGL2RenderingContext !== 'undefined' && gl instanceof WebGL2RenderingContext ?
      'webgl2' :
      'webgl';
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  container.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color('#15171c');
  const frame = sceneFrame();
  const camera = new THREE.PerspectiveCamera(50, 1, frame.radius * 1e-3, frame.radius * 200);
  camera.up.copy(frame.up);
  const side = new THREE.Vector3(1, 0, 0);
  if (Math.abs(side.dot(frame.up)) > 0.9) side.set(0, 1, 0);
  side.sub(frame.up.clone().multiplyScalar(side.dot(frame.up))).normalize();
  camera.position.copy(frame.center)
      .add(frame.up.clone().multiplyScalar(1.6 * frame.radius))
      .add(side.multiplyScalar(1.9 * frame.radius));
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(frame.center);
  controls.update();

  const layers = [];
  const addLayer = (set, color, isReference) => {
    const group = new THREE.Group();
    const frusta = new THREE.LineSegments(
        frustaGeometry(set.images, frustumSize(set, frame.radius)),
        new THREE.LineBasicMaterial({vertexColors: true}));
    group.add(frusta);
    const trajectory = set.sequence ? trajectoryObject(set.images, color) : null;
    if (trajectory) group.add(trajectory);
    const points = pointsObject(set.points, frame);
    if (points) group.add(points);
    scene.add(group);
    layers.push({set, color, isReference, group, frusta, trajectory});
  };
  if (reference) addLayer(reference, REFERENCE_COLOR, true);
  models.forEach((model) => addLayer(model, model.color, false));

  const render = () => renderer.render(scene, camera);
  const resize = () => {
    const width = container.clientWidth;
    const height = container.clientHeight;
    renderer.setSize(width, height, false);
    renderer.domElement.style.width = width + 'px';
    renderer.domElement.style.height = height + 'px';
    camera.aspect = width / Math.max(1, height);
    camera.updateProjectionMatrix();
    render();
  };
  controls.addEventListener('change', render);
  window.addEventListener('resize', resize);
  return {renderer, scene, camera, controls, layers, render, resize, radius: frame.radius};
}

// Each layer's frusta coloured by `metric` on one shared scale (95th percentile of the visible).
function colorFrusta(view, metric) {
  const visible = view.layers.filter((layer) => layer.group.visible && !layer.isReference);
  const values = [];
  for (const layer of visible) {
    const list = layer.set.images[metric];
    if (Array.isArray(list)) {
      for (const v of list)
        if (v !== null) values.push(v);
    }
  }
  // From 0 to the 95th percentile, but never below what is small for the metric, so that
  // uniformly good cameras stay green.
  const floor = {
    rotation_error_deg: 0.5,
    position_error: 0.01 * view.radius,
    reprojection_error_px: 2
  }[metric] ||
      1e-9;
  const scale = Math.max(quantile(values, 0.95) || 0, floor);
  for (const layer of view.layers) {
    const list = layer.set.images[metric];
    const colors = layer.frusta.geometry.getAttribute('color');
    const own = hexToRgb(layer.color);
    for (let k = 0; k < layer.set.images.name.length; ++k) {
      let rgb = own;
      if (!layer.isReference && metric !== 'model') {
        rgb = Array.isArray(list) && list[k] !== null ? ramp(list[k] / scale) : [0.55, 0.55, 0.6];
      }
      for (let v = 0; v < 16; ++v) colors.setXYZ(16 * k + v, rgb[0], rgb[1], rgb[2]);
    }
    colors.needsUpdate = true;
  }
  const legend = document.getElementById('legend');
  legend.replaceChildren();
  if (metric === 'model') {
    legend.append(element('div', {text: 'frusta in their model\'s colour'}));
  } else {
    const label = METRICS.find((m) => m.key === metric).label;
    legend.append(
        element('div', {text: label}), element('div', {class: 'ramp'}),
        element('div', {class: 'ends'}, [
          element('span', {text: '0'}), element('span', {text: '≥ ' + Number(scale.toPrecision(3))})
        ]));
  }
  view.render();
}

function renderViewControls(view) {
  const controls = document.getElementById('view-controls');
  const metrics = availableMetrics();
  const select = element(
      'select', {id: 'metric'},
      metrics.map((m) => element('option', {value: m.key, text: m.label})));
  controls.append(element('label', {text: 'Colour cameras by '}, [select]));
  let metric = metrics[0].key;
  select.addEventListener('change', () => {
    metric = select.value;
    colorFrusta(view, metric);
  });
  if (view.layers.some((layer) => layer.trajectory)) {
    const paths = element('input', {type: 'checkbox', id: 'trajectories'});
    paths.checked = true;
    paths.addEventListener('change', () => {
      for (const layer of view.layers)
        if (layer.trajectory) layer.trajectory.visible = paths.checked;
      view.render();
    });
    controls.append(element('label', {}, [paths, ' trajectories (capture order)']));
  }
  for (const layer of view.layers) {
    const box = element('input', {type: 'checkbox', 'data-model': layer.set.name});
    box.checked = layer.isReference || layer === view.layers.find((l) => !l.isReference) ||
        data.kind === 'compare';
    layer.group.visible = box.checked;
    box.addEventListener('change', () => {
      layer.group.visible = box.checked;
      colorFrusta(view, metric);
    });
    controls.append(element('label', {}, [
      box, element('span', {class: 'swatch', style: 'background:' + layer.color}),
      layer.set.name + ' (' + layer.set.images.name.length + ')'
    ]));
  }
  colorFrusta(view, metric);
  return (name, visible) => {
    const box = controls.querySelector('input[data-model="' + CSS.escape(name) + '"]');
    if (!box) throw new Error('no model named ' + name);
    box.checked = visible;
    box.dispatchEvent(new Event('change'));
  };
}

// ---------------------------------------------------------------- plots (SVG)
function niceTicks(low, high, count) {
  const span = high - low || 1;
  const step0 = Math.pow(10, Math.floor(Math.log10(span / count)));
  const step = [1, 2, 5, 10].map((m) => m * step0).find((s) => span / s <= count) || 10 * step0;
  const ticks = [];
  for (let t = Math.ceil(low / step) * step; t <= high + 1e-9 * span; t += step)
    ticks.push(Number(t.toPrecision(12)));
  return ticks;
}

// Legend entries laid out left to right from (left, y), wrapping at `right` (11 px text is
// about 6 px a character): each entry's position, and the y below the last row.
function flowLegend(labels, left, right, y) {
  const positions = [];
  let x = left;
  for (const label of labels) {
    const width = 14 + 6 * label.length + 16;
    if (x > left && x + width > right) {
      x = left;
      y += 14;
    }
    positions.push([x, y]);
    x += width;
  }
  return {positions, bottom: y};
}

// A line plot: series of [x, y] (y null: a gap), linear x, linear or log y, a legend, and a
// readout of the values under the pointer.
function linePlot(container, options) {
  const width = 640, height = 310, left = 58, right = 14, bottom = 42;
  const legend = flowLegend(options.series.map((series) => series.name), left, width - right, 34);
  const top = legend.bottom + 8;
  const plot = element('div', {class: 'plot'});
  const root = svg(
      'svg', {viewBox: '0 0 ' + width + ' ' + height, role: 'img', 'aria-label': options.title});
  const all =
      options.series.flatMap((s) => s.points.filter((p) => p[1] !== null && isFinite(p[1])));
  const xs = all.map((p) => p[0]);
  const ys = all.map((p) => p[1]);
  const xMin = options.xMin !== undefined ? options.xMin : minimum(xs, 0);
  const xMax = options.xMax !== undefined ? options.xMax : maximum(xs, 1);
  let yMin = options.yMin !== undefined ? options.yMin : minimum(ys, 0);
  let yMax = options.yMax !== undefined ? options.yMax : maximum(ys, 1e-12);
  const log = options.logY && ys.some((y) => y > 0);
  if (log) {
    const positive = ys.filter((y) => y > 0);
    yMin = Math.pow(
        10,
        Math.floor(Math.log10(Math.max(quantile(positive, 0.01), maximum(positive, 0) * 1e-4))));
    yMax = Math.pow(10, Math.ceil(Math.log10(maximum(positive, 0))));
    if (yMax <= yMin) yMax = yMin * 10;
  }
  const X = (x) => left + (x - xMin) / (xMax - xMin || 1) * (width - left - right);
  const Y = (y) => {
    const t = log ?
        (Math.log10(Math.max(y, yMin)) - Math.log10(yMin)) / (Math.log10(yMax) - Math.log10(yMin)) :
        (y - yMin) / (yMax - yMin || 1);
    return height - bottom - Math.max(0, Math.min(1, t)) * (height - top - bottom);
  };
  root.append(svg('text', {x: left, y: 14, 'font-weight': 600}, options.title));
  const yTicks = log ? (() => {
    const t = [];
    for (let v = yMin; v <= yMax * 1.0001; v *= 10) t.push(v);
    return t;
  })() :
                       niceTicks(yMin, yMax, 5);
  for (const t of yTicks) {
    root.append(svg('line', {class: 'grid', x1: left, x2: width - right, y1: Y(t), y2: Y(t)}));
    root.append(
        svg('text', {x: left - 6, y: Y(t) + 4, 'text-anchor': 'end'},
            Number(t.toPrecision(3)).toString()));
  }
  for (const t of niceTicks(xMin, xMax, 8)) {
    root.append(
        svg('text', {x: X(t), y: height - bottom + 16, 'text-anchor': 'middle'}, String(t)));
  }
  const axis = svg('g', {class: 'axis'});
  axis.append(svg('line', {x1: left, x2: width - right, y1: height - bottom, y2: height - bottom}));
  axis.append(svg('line', {x1: left, x2: left, y1: top, y2: height - bottom}));
  root.append(axis);
  root.append(
      svg('text', {x: (left + width - right) / 2, y: height - 6, 'text-anchor': 'middle'},
          options.xLabel));
  root.append(
      svg('text', {
        x: 12,
        y: (top + height - bottom) / 2,
        'text-anchor': 'middle',
        transform: 'rotate(-90 12 ' + (top + height - bottom) / 2 + ')'
      },
          options.yLabel + (log ? ' (log)' : '')));
  options.series.forEach((series, k) => {
    let path = '';
    let pen = false;
    for (const [x, y] of series.points) {
      if (y === null || !isFinite(y)) {
        pen = false;
        continue;
      }
      path += (pen ? 'L' : 'M') + X(x).toFixed(1) + ' ' + Y(y).toFixed(1);
      pen = true;
    }
    const line = svg('path', {
      d: path || 'M0 0',
      fill: 'none',
      stroke: series.color,
      'stroke-width': series.width || 1.6
    });
    line.append(svg('title', {}, series.name));
    root.append(line);
    const [lx, ly] = legend.positions[k];
    root.append(svg('rect', {x: lx, y: ly - 7, width: 10, height: 3, fill: series.color}));
    root.append(svg('text', {x: lx + 14, y: ly - 2}, series.name));
  });
  const cursor = svg('line', {
    x1: 0,
    x2: 0,
    y1: top,
    y2: height - bottom,
    stroke: '#888',
    'stroke-dasharray': '3 3',
    visibility: 'hidden'
  });
  root.append(cursor);
  const readout = element('div', {class: 'readout'});
  if (options.readout) {
    root.addEventListener('mousemove', (event) => {
      const box = root.getBoundingClientRect();
      const px = (event.clientX - box.left) / box.width * width;
      const x = xMin + (px - left) / (width - left - right) * (xMax - xMin);
      if (x < xMin || x > xMax) return;
      cursor.setAttribute('x1', px);
      cursor.setAttribute('x2', px);
      cursor.setAttribute('visibility', 'visible');
      readout.textContent = options.readout(x);
    });
  }
  plot.append(root, readout);
  container.append(plot);
  return plot;
}

function renderRecallPlot(container) {
  const curves = data.recall_curves || [];
  if (curves.length === 0) return;
  const series = curves.map((curve) => ({
                              name: curve.name +
                                  (curve.auc && curve.auc['3'] !== undefined ?
                                       ' (AUC@3 ' + fixed(curve.auc['3'], 1) + ')' :
                                       ''),
                              color: colorOf(curve.name),
                              points: curve.threshold_deg.map((t, k) => [t, 100 * curve.recall[k]]),
                            }));
  linePlot(container, {
    title: 'Relative pose recall against error threshold (its area is the AUC)',
    xLabel: 'threshold (deg)',
    yLabel: 'pairs within (%)',
    series,
    yMin: 0,
    yMax: 100,
    xMin: 0,
    readout: (x) =>
        curves
            .map((curve) => {
              const k = Math.round(
                  x / curve.threshold_deg[curve.threshold_deg.length - 1] *
                  (curve.threshold_deg.length - 1));
              return curve.name + ' ' +
                  fixed(100 * curve.recall[Math.max(0, Math.min(k, curve.recall.length - 1))], 1) +
                  '%';
            })
            .join(' · ') +
        ' within ' + fixed(x, 2) + ' deg',
  });
}

function renderPerImagePlots(container) {
  const order = data.image_order || [];
  const position = new Map(order.map((name, k) => [name, k]));
  const plots = [
    {key: 'rotation_error_deg', title: 'Rotation error per image, after alignment', unit: 'deg'},
    {
      key: 'position_error',
      title: 'Position error per image, after alignment',
      unit: data.position_unit || 'reference units'
    },
    {key: 'reprojection_error_px', title: 'Mean reprojection error per image', unit: 'px'},
  ];
  for (const spec of plots) {
    const withValues = models.filter(
        (m) => Array.isArray(m.images[spec.key]) && m.images[spec.key].some((v) => v !== null));
    if (withValues.length === 0) continue;
    if (spec.key === 'reprojection_error_px' && data.kind === 'compare') continue;
    const series = withValues.map((model) => {
      let extra = order.length;  // names the order lacks go after it, in the model's order
      const points = model.images.name.map(
          (name,
           k) => [position.has(name) ? position.get(name) : extra++, model.images[spec.key][k]]);
      points.sort((a, b) => a[0] - b[0]);
      return {name: model.name, color: model.color, points, width: 1.2};
    });
    linePlot(container, {
      title: spec.title,
      xLabel: 'image, in capture order',
      yLabel: spec.unit,
      series,
      logY: true,
      xMin: 0,
      xMax: Math.max(
          order.length - 1, maximum(withValues.map((m) => m.images.name.length), 0) - 1, 1),
      readout: (x) => {
        const k = Math.round(x);
        const name = order[k] || '';
        return name + ': ' +
            withValues
                .map((model) => {
                  const i = model.images.name.indexOf(name);
                  return model.name + ' ' +
                      (i < 0 ? 'not registered' : fixed(model.images[spec.key][i], 4));
                })
                .join(' · ');
      },
    });
  }
}

function renderStagePlot(container) {
  const bars = data.stage_seconds || [];
  if (bars.length === 0) return;
  const stageNames = [];
  for (const bar of bars)
    for (const [stage] of bar.stages)
      if (!stageNames.includes(stage)) stageNames.push(stage);
  const stageColor = (stage) => PALETTE[stageNames.indexOf(stage) % PALETTE.length];
  const width = 640, left = 96, right = 60, rowHeight = 26, top = 26;
  const axisY = top + bars.length * rowHeight + 2;
  const legend = flowLegend(stageNames, left, width, axisY + 28);
  const height = legend.bottom + 12;
  const total = maximum(bars.map((bar) => bar.stages.reduce((sum, [, s]) => sum + s, 0)), 1e-9);
  const X = (s) => left + s / total * (width - left - right);
  const plot = element('div', {class: 'plot'});
  const root = svg(
      'svg', {viewBox: '0 0 ' + width + ' ' + height, role: 'img', 'aria-label': 'stage times'});
  root.append(svg('text', {x: left, y: 14, 'font-weight': 600}, 'Wall time per stage (seconds)'));
  bars.forEach((bar, row) => {
    const y = top + row * rowHeight;
    root.append(svg('text', {x: left - 6, y: y + 15, 'text-anchor': 'end'}, bar.name));
    let at = 0;
    for (const [stage, seconds] of bar.stages) {
      const rect = svg('rect', {
        x: X(at),
        y: y + 3,
        width: Math.max(0, X(at + seconds) - X(at)),
        height: rowHeight - 8,
        fill: stageColor(stage)
      });
      rect.append(svg('title', {}, bar.name + ': ' + stage + ' ' + fixed(seconds, 3) + ' s'));
      root.append(rect);
      at += seconds;
    }
    root.append(svg('text', {x: X(at) + 5, y: y + 15}, fixed(at, 2) + ' s'));
  });
  for (const t of niceTicks(0, total, 6))
    root.append(svg('text', {x: X(t), y: axisY + 12, 'text-anchor': 'middle'}, String(t)));
  stageNames.forEach((stage, k) => {
    const [lx, ly] = legend.positions[k];
    root.append(svg('rect', {x: lx, y: ly - 9, width: 10, height: 10, fill: stageColor(stage)}));
    root.append(svg('text', {x: lx + 14, y: ly}, stage));
  });
  plot.append(root);
  container.append(plot);
}

// ---------------------------------------------------------------- the mapper's summary
function objectTable(list, limit) {
  const keys = [];
  for (const item of list)
    for (const key of Object.keys(item))
      if (!keys.includes(key)) keys.push(key);
  const rows = list.slice(0, limit).map((item) => keys.map((key) => {
    const v = item[key];
    if (typeof v === 'number') return Number.isInteger(v) ? v : Number(v.toPrecision(5));
    return typeof v === 'object' && v !== null ? JSON.stringify(v) : v;
  }));
  const node = table(keys, rows);
  node.querySelectorAll('td').forEach((td) => {
    if (isNaN(Number(td.textContent))) td.classList.add('text');
  });
  return node;
}

function renderSummary(section) {
  const summary = data.summary;
  if (!summary) return;
  section.append(element('h2', {text: data.summary_title || 'The mapper\'s summary'}));
  section.append(element('p', {
    text: summary.num_registered_images + ' of ' + summary.num_images + ' images registered in ' +
        (summary.components || []).length + ' model(s); ' + summary.num_verified_pairs +
        ' verified pairs, ' + summary.num_relative_poses + ' relative poses; ' +
        fixed(summary.total_seconds, 2) + ' s, peak memory ' + fixed(summary.peak_rss_mib, 0) +
        ' MiB.'
  }));
  const components = summary.components || [];
  if (components.length) {
    section.append(element('h3', {text: 'Models and the rotation certificate'}));
    section.append(table(
        [
          'model', 'images', 'points', 'mean reproj. error (px)', 'certified globally optimal',
          'certificate bound (deg)', 'max rotation residual (deg)', 'pruned edges',
          'BA RMSE before / after (px)'
        ],
        components.map((c, k) => {
          const ra = c.rotation_averaging || {};
          const ba = c.bundle_adjustment;
          return [
            String(k), c.num_images, c.num_points, fixed(c.mean_reprojection_error_px, 3),
            element('span', {
              class: ra.certified_globally_optimal ? 'tag' : 'tag no',
              text: ra.certified_globally_optimal ? 'yes' : 'no'
            }),
            fixed(ra.certificate_bound_deg, 3), fixed(ra.max_residual_deg, 3), ra.num_pruned_edges,
            ba ? fixed(ba.initial_rmse_px, 3) + ' / ' + fixed(ba.final_rmse_px, 3) : 'no BA'
          ];
        })));
  }
  const cameras = summary.cameras || [];
  if (cameras.length) {
    section.append(element('h3', {text: 'Cameras: focal length given (EXIF, the user) or guessed, view-graph estimate, final'}));
    section.append(table(
        ['camera', 'model', 'focal length given', 'given or guessed', 'view-graph estimate', 'final'],
        cameras.map((c) => {
          const vg = c.view_graph_calibration;
          let estimate = 'not run';
          if (vg) {
            const value = vg.estimated_focal_px ? fixed(vg.estimated_focal_px, 1) + ' px' : '';
            if (vg.outcome === 'given, confirmed')
              estimate = value + ': confirms the given focal length';
            else if (vg.outcome === 'given, disproved')
              estimate = value + ': disproves the given focal length, which it replaces';
            else if (vg.estimated)
              estimate = value;
            else
              estimate = 'kept the prior: ' + (vg.problem || 'not estimated');
          }
          const params = (p) =>
              (p || []).map((v) => (v === null ? 'NaN' : Number(v.toPrecision(6)))).join(', ');
          return [
            String(c.camera_id), c.model,
            element('span', {
              class: 'wrap',
              text: (c.prior_focal_length_known ? 'yes' : 'no') +
                  (c.focal_source ? ': ' + c.focal_source : '')
            }),
            params(c.prior_params), element('span', {class: 'wrap', text: estimate}),
            params(c.final_params)
          ];
        })));
  }
  const dropped = summary.dropped_images || [];
  section.append(element('h3', {text: 'Dropped images (' + dropped.length + ')'}));
  section.append(
      dropped.length ?
          objectTable(dropped, 500) :
          element('p', {text: 'None: every image with a verified pair was registered.'}));
  const edges = summary.dropped_edges || [];
  const edgeDetails = element(
      'details', {}, [element('summary', {
        text: 'Dropped pairs (' + edges.length + ')' + (edges.length > 300 ? ', the first 300' : '')
      })]);
  if (edges.length) edgeDetails.append(objectTable(edges, 300));
  section.append(edgeDetails);
  const options = summary.run && summary.run.options;
  if (options) {
    const details = element('details', {}, [element('summary', {text: 'Options used'})]);
    details.append(element('pre', {text: JSON.stringify(options, null, 1)}));
    section.append(details);
  }
  const whole = element('details', {}, [element('summary', {text: 'summary.json, whole'})]);
  whole.append(element('pre', {text: JSON.stringify(summary, null, 1)}));
  section.append(whole);
}

// ---------------------------------------------------------------- assembly
// How many cameras a layer should show, from outside the drawn model's own arrays: the mapper's
// summary (its components' image counts) or the comparison (each run's registered images);
// the reference's, from its poses.
function expectedCameras(layer) {
  if (layer.isReference) return layer.set.num_registered;
  if (data.comparison) {
    const run = data.comparison.runs.find((r) => r.name === layer.set.name);
    return run ? run.num_registered : null;
  }
  const k = models.indexOf(layer.set);
  const components = (data.summary && data.summary.components) || [];
  return k >= 0 && k < components.length ? components[k].num_images : null;
}

// Runs one part of the page: a part that fails says so where it would have been (and on the
// console, where the browser test sees it) and leaves the other parts whole.
function drawPart(what, container, draw) {
  try {
    return draw();
  } catch (error) {
    console.error('report.html: ' + what + ' could not be drawn: ' + error);
    container.append(element('p', {class: 'hint', text: what + ' could not be drawn: ' + error}));
    return null;
  }
}

function main() {
  renderHeader();
  const results = document.getElementById('results');
  const plots = document.getElementById('plots');
  const summary = document.getElementById('summary');
  drawPart('the comparison table', results, () => renderComparison(results));
  drawPart('the recall curves', plots, () => renderRecallPlot(plots));
  drawPart('the per-image errors', plots, () => renderPerImagePlots(plots));
  drawPart('the stage times', plots, () => renderStagePlot(plots));
  drawPart('the summary', summary, () => renderSummary(summary));
  const scene = document.getElementById('scene');
  const view = models.length ? drawPart('the 3D view', scene, buildView) : null;
  if (view) {
    report.view = view;
    report.setVisible = drawPart('the view\'s controls', scene, () => renderViewControls(view));
    view.resize();
  } else if (!models.length) {
    scene.hidden = true;
  }
  // What the browser test reads: every layer's drawn frusta against its registered images.
  report.state = () => ({
    webgl: report.webgl,
    layers: view ?
        view.layers.map((layer) => ({
                          name: layer.set.name,
                          reference: layer.isReference,
                          visible: layer.group.visible,
                          frusta: layer.frusta.geometry.getAttribute('position').count / 16,
                          registered: layer.set.num_registered,
                          expected: expectedCameras(layer),
                        })) :
        [],
    camera: view ? view.camera.position.toArray() : null,
  });
  // Pixels of the last frame that differ from the background.
  report.litPixels = () => {
    if (!view) return 0;
    view.render();
    const gl = view.renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const pixels = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    let lit = 0;
    for (let k = 0; k < pixels.length; k += 4) {
      if (Math.abs(pixels[k] - 0x15) + Math.abs(pixels[k + 1] - 0x17) +
              Math.abs(pixels[k + 2] - 0x1c) >
          24)
        ++lit;
    }
    return lit;
  };
  report.ready = true;
}

main();
})();
