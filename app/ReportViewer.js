// The page of an HTML report (app/HtmlReport): the table and the 3D view,
// built from the JSON in #dfrecon-data with three.js (inlined before this).
// The page says what it drew on its body (data-webgl, data-surfaces, and
// data-view: the anatomical view shown), which the tests read.
(function () {
  'use strict';
  const dataElement = document.getElementById('dfrecon-data');
  const data = JSON.parse(dataElement.textContent);
  // The embedded text is most of the page: once parsed it is dropped from
  // the document, so the page does not hold it twice.
  dataElement.remove();
  document.title = data.title;
  document.getElementById('title').textContent = data.title;

  function bytes(text) {
    const raw = atob(text);
    const out = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; ++i) out[i] = raw.charCodeAt(i);
    return out;
  }
  // Buffers come deflated (zlib format): the browser's own decompressor
  // inflates them, from file:// and with no network.
  async function inflated(text) {
    const stream = new Blob([bytes(text)]).stream().pipeThrough(new DecompressionStream('deflate'));
    return new Response(stream).arrayBuffer();
  }
  function cell(value) {
    if (value === null || value === undefined) return '';
    if (typeof value === 'number' && !Number.isInteger(value)) return value.toPrecision(6);
    return String(value);
  }

  // ---- the table: one row per result; a surface's row has its colour, a
  // box that shows or hides it and a slider for its opacity. Headers sort.
  const meshes = {};
  const controlsOf = {};  // name -> {box, slider}
  const table = document.createElement('table');
  const head = table.createTHead().insertRow();
  const body = table.createTBody();
  const surfaceNames = new Set(data.surfaces.map((s) => s.name));
  let sortColumn = -1, sortUp = true;
  data.columns.forEach((column, k) => {
    const th = document.createElement('th');
    th.textContent = column;
    th.title = 'Sort by ' + column;
    th.onclick = () => {
      sortUp = sortColumn === k ? !sortUp : true;
      sortColumn = k;
      const rows = Array.from(body.rows);
      const key = (tr) => tr.dataset['v' + k];
      rows.sort((a, b) => {
        const x = key(a), y = key(b);
        const nx = parseFloat(x), ny = parseFloat(y);
        const order = !isNaN(nx) && !isNaN(ny) ? nx - ny : x.localeCompare(y);
        return sortUp ? order : -order;
      });
      for (const tr of rows) body.appendChild(tr);
      for (const other of head.cells) other.dataset.sort = '';
      th.dataset.sort = sortUp ? 'up' : 'down';
    };
    head.appendChild(th);
  });
  for (const row of data.rows) {
    const tr = body.insertRow();
    data.columns.forEach((column, k) => {
      const td = tr.insertCell();
      const text = cell(row[column]);
      tr.dataset['v' + k] = text;
      if (k === 0 && surfaceNames.has(text)) {
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.checked = true;
        box.title = 'Show or hide';
        box.onchange = () => { if (meshes[text]) { meshes[text].visible = box.checked; draw(); } };
        const slider = document.createElement('input');
        slider.type = 'range';
        slider.min = '0';
        slider.max = '100';
        slider.value = '100';
        slider.className = 'opacity';
        slider.title = 'Opacity';
        slider.oninput = () => { setOpacity(text, slider.value / 100); draw(); };
        controlsOf[text] = {box, slider};
        const s = data.surfaces.find((x) => x.name === text);
        td.append(box);
        // A surface coloured by its values has no one colour to show.
        if (!s.pointColours) {
          const swatch = document.createElement('span');
          swatch.className = 'swatch';
          swatch.style.background = 'rgb(' + s.colour.join(',') + ')';
          td.append(swatch);
        }
        td.append(text, slider);
      } else {
        td.append(text);
      }
    });
  }
  document.getElementById('table').appendChild(table);
  if (data.note) {
    const p = document.createElement('p');
    p.textContent = data.note;
    document.getElementById('side').appendChild(p);
  }
  if (data.valueName) {
    document.getElementById('legend').textContent = 'Colours: ' + data.valueName +
        ', blue (−' + data.valueScaleMm.toPrecision(3) + ') to white (0) to red (+' +
        data.valueScaleMm.toPrecision(3) + ').';
  }

  // ---- the 3D view, in patient coordinates (LPS, mm: +x the patient's
  // left, +y posterior, +z superior).
  const view = document.getElementById('view');
  const note = document.getElementById('note');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (error) {
    note.textContent = 'This browser has no WebGL: the table holds every figure.';
    document.body.dataset.webgl = '0';
    document.body.dataset.surfaces = '0';
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x20242a);
  const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1e5);
  camera.up.set(0, 0, 1);
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  const light = new THREE.DirectionalLight(0xffffff, 0.75);
  camera.add(light);
  scene.add(camera);

  function setOpacity(name, opacity) {
    const mesh = meshes[name];
    if (!mesh) return;
    mesh.material.opacity = opacity;
    mesh.material.transparent = opacity < 1;
    // A translucent outline must not hide what lies inside it.
    mesh.material.depthWrite = opacity >= 1;
    mesh.renderOrder = opacity < 1 ? 1 : 0;
    if (controlsOf[name]) controlsOf[name].slider.value = String(Math.round(opacity * 100));
  }

  // The surface as app/HtmlReport wrote it: 16-bit positions across its box,
  // corner indices as zigzag differences, each deflated.
  async function surfaceGeometry(s) {
    const steps = new Uint16Array(await inflated(s.positions));
    const positions = new Float32Array(steps.length);
    for (let i = 0; i < steps.length; ++i) positions[i] = s.boxMinMm[i % 3] + steps[i] * s.stepMm[i % 3];
    const deltas = new Int32Array(await inflated(s.corners));
    const corners = new Uint32Array(deltas.length);
    let previous = 0;
    for (let i = 0; i < deltas.length; ++i) {
      const d = deltas[i];
      previous += (d & 1) ? -((d + 1) / 2) : d / 2;
      corners[i] = previous;
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    geometry.setIndex(new THREE.BufferAttribute(corners, 1));
    geometry.computeVertexNormals();
    if (s.pointColours)
      geometry.setAttribute('color', new THREE.BufferAttribute(new Uint8Array(await inflated(s.pointColours)), 3, true));
    return geometry;
  }

  // Anatomical views: where the camera stands (from the centre) and which
  // way is up on the screen. Anterior: the patient's right on the viewer's
  // left, as a planning system shows it.
  const views = {
    anterior: {from: [0, -1, 0], up: [0, 0, 1]},
    posterior: {from: [0, 1, 0], up: [0, 0, 1]},
    left: {from: [1, 0, 0], up: [0, 0, 1]},
    right: {from: [-1, 0, 0], up: [0, 0, 1]},
    superior: {from: [0, 0, 1], up: [0, -1, 0]},
    inferior: {from: [0, 0, -1], up: [0, -1, 0]},
  };
  let centre = new THREE.Vector3(), radius = 100, controls;
  function showView(name) {
    const v = views[name];
    camera.up.set(v.up[0], v.up[1], v.up[2]);
    camera.position.copy(centre).add(new THREE.Vector3(v.from[0], v.from[1], v.from[2]).multiplyScalar(4 * radius));
    camera.lookAt(centre);
    if (controls) {
      controls.dispose();
    }
    // OrbitControls take the camera's up as theirs when made.
    controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(centre);
    controls.addEventListener('change', draw);
    controls.update();
    document.body.dataset.view = name;
    draw();
  }
  const buttons = document.createElement('div');
  buttons.id = 'views';
  for (const name of Object.keys(views)) {
    const button = document.createElement('button');
    button.textContent = name[0].toUpperCase() + name.slice(1);
    button.onclick = () => showView(name);
    buttons.appendChild(button);
  }
  view.appendChild(buttons);

  // The orientation marker: the patient's axes as the camera sees them,
  // each end labelled (L/R, A/P, S/I), in the corner of the view.
  const svgNs = 'http://www.w3.org/2000/svg';
  const marker = document.createElementNS(svgNs, 'svg');
  marker.setAttribute('id', 'marker');
  marker.setAttribute('viewBox', '-50 -50 100 100');
  const axes = [['L', 'R', [1, 0, 0], '#e06060'], ['P', 'A', [0, 1, 0], '#60c060'], ['S', 'I', [0, 0, 1], '#6080e0']];
  const parts = axes.map(([plus, minus, , colour]) => {
    const line = document.createElementNS(svgNs, 'line');
    line.setAttribute('stroke', colour);
    line.setAttribute('stroke-width', '3');
    marker.appendChild(line);
    const labels = [plus, minus].map((text) => {
      const label = document.createElementNS(svgNs, 'text');
      label.textContent = text;
      label.setAttribute('fill', colour);
      label.setAttribute('font-size', '16');
      label.setAttribute('text-anchor', 'middle');
      label.setAttribute('dominant-baseline', 'central');
      marker.appendChild(label);
      return label;
    });
    return {line, labels};
  });
  view.appendChild(marker);
  function drawMarker() {
    const toView = camera.quaternion.clone().invert();
    axes.forEach(([, , direction], k) => {
      const v = new THREE.Vector3(direction[0], direction[1], direction[2]).applyQuaternion(toView);
      const x = 30 * v.x, y = -30 * v.y;
      parts[k].line.setAttribute('x1', String(-x));
      parts[k].line.setAttribute('y1', String(-y));
      parts[k].line.setAttribute('x2', String(x));
      parts[k].line.setAttribute('y2', String(y));
      parts[k].labels[0].setAttribute('x', String(1.4 * x));
      parts[k].labels[0].setAttribute('y', String(1.4 * y));
      parts[k].labels[1].setAttribute('x', String(-1.4 * x));
      parts[k].labels[1].setAttribute('y', String(-1.4 * y));
    });
  }

  function resize() {
    const width = view.clientWidth, height = view.clientHeight;
    renderer.setSize(width, height);
    camera.aspect = width / Math.max(1, height);
    camera.updateProjectionMatrix();
    draw();
  }
  function draw() {
    renderer.render(scene, camera);
    drawMarker();
  }

  (async function build() {
    const box = new THREE.Box3();
    const boxes = {};
    for (const s of data.surfaces) {
      const geometry = await surfaceGeometry(s);
      const options = {side: THREE.DoubleSide, shininess: 20};
      if (s.pointColours) options.vertexColors = true;
      else options.color = new THREE.Color(s.colour[0] / 255, s.colour[1] / 255, s.colour[2] / 255);
      s.positions = s.corners = s.pointColours = undefined;  // decoded: the text can go
      const mesh = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial(options));
      mesh.name = s.name;
      meshes[s.name] = mesh;
      scene.add(mesh);
      geometry.computeBoundingBox();
      boxes[s.name] = geometry.boundingBox;
      box.union(geometry.boundingBox);
    }
    // An outline that holds other surfaces (a body, a lung around its
    // tumour) starts translucent, so that they show.
    for (const s of data.surfaces)
      if (data.surfaces.some((t) => t.name !== s.name && boxes[s.name].containsBox(boxes[t.name])))
        setOpacity(s.name, 0.3);
    if (!box.isEmpty()) {
      centre = box.getCenter(new THREE.Vector3());
      radius = Math.max(1, box.getSize(new THREE.Vector3()).length() / 2);
    }
    // The bounding sphere fits a 35° view at 3.2 radii; 4 leaves a margin.
    camera.near = radius / 100;
    camera.far = radius * 100;
    const asked = /view=(\w+)/.exec(window.location.hash);
    window.addEventListener('resize', resize);
    resize();
    showView(asked && views[asked[1]] ? asked[1] : 'anterior');
    document.body.dataset.webgl = '1';
    document.body.dataset.surfaces = String(data.surfaces.length);
  })().catch((error) => {
    note.textContent = 'The surfaces could not be decoded: ' + error;
    document.body.dataset.webgl = '1';
    document.body.dataset.surfaces = '0';
  });
})();
