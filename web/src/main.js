// The globalvis viewer (paper §7.4-§7.5): a static page with the scene, its cells, portals and
// links; click a patch to see what it sees, pick one of its interactions to see tube and blockers.
// State for scripts and tests: window.viewerState; actions: window.viewerApi.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { COLORS, buildLayers } from './layers.js';
import { createPanel } from './panel.js';
import { readEmbeddedData, unpackPairs, unpackPolygons, upAxis } from './scene_data.js';
import { pairSelectionGroup, patchSelectionGroup } from './selection.js';

/** A click is a pick only if the pointer moved less than this many pixels (else it orbited). */
const CLICK_SLOP_PIXELS = 4;

function start() {
  const data = readEmbeddedData(document);
  const patchCount = data.patches.sizes.length;
  const pairs = unpackPairs(data.pairs, patchCount);
  const lo = new THREE.Vector3(...data.bounds.min);
  const hi = new THREE.Vector3(...data.bounds.max);
  const diagonal = lo.distanceTo(hi) || 1;
  const center = lo.clone().add(hi).multiplyScalar(0.5);
  const up = upAxis(unpackPolygons(data.patches), (i) => {
    const m = data.materials[data.patches.material[i]];
    return !!m && Math.max(...m.ke) > 0;
  });
  const upVector = new THREE.Vector3().setComponent(up, 1);
  const loUp = lo.getComponent(up);
  const hiUp = hi.getComponent(up);

  const state = {
    ready: false,
    frames: 0,
    patchCount,
    pairCount: pairs.count,
    selectedPatch: null,
    selectedPair: null,
    shading: data.elements || data.radiosity ? 'radiosity' : 'material',
    show: { cells: false, portals: false, visibleLinks: false, partialLinks: false },
    upAxis: up,
    sectionHeight: loUp + 0.8 * (hiUp - loUp),
  };
  window.viewerState = state;

  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.outputColorSpace = THREE.LinearSRGBColorSpace;  // colours are display values already
  renderer.localClippingEnabled = true;
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(COLORS.background);
  document.body.appendChild(renderer.domElement);
  renderer.domElement.id = 'gv-canvas';

  // Keeps what is below the section height along the up axis.
  const section = new THREE.Plane(upVector.clone().negate(), state.sectionHeight);
  const layers = buildLayers(data, pairs, [section]);
  const scene = new THREE.Scene();
  scene.add(layers.surfaces.material);
  if (layers.surfaces.radiosity) scene.add(layers.surfaces.radiosity);
  for (const name of ['cells', 'portals', 'visibleLinks', 'partialLinks']) {
    if (layers[name]) scene.add(layers[name]);
  }
  let overlay = null;

  const camera = new THREE.PerspectiveCamera(45, 1, diagonal * 1e-3, diagonal * 20);
  camera.up.copy(upVector);
  const controls = new OrbitControls(camera, renderer.domElement);
  const resetView = () => {
    // From above and in front: 0.95 along up, -0.75 and -0.25 along the next two axes.
    const offset = new THREE.Vector3()
      .setComponent(up, 0.95)
      .setComponent((up + 1) % 3, -0.25)
      .setComponent((up + 2) % 3, -0.75);
    camera.position.copy(center).add(offset.multiplyScalar(diagonal * 0.85));
    controls.target.copy(center);
    controls.update();
  };
  resetView();

  function render() {
    const radiosity = state.shading === 'radiosity' && layers.surfaces.radiosity;
    layers.surfaces.material.visible = !radiosity;
    if (layers.surfaces.radiosity) layers.surfaces.radiosity.visible = !!radiosity;
    const selecting = state.selectedPatch !== null || state.selectedPair !== null;
    if (layers.cells) layers.cells.visible = state.show.cells;
    if (layers.portals) layers.portals.visible = state.show.portals;
    layers.visibleLinks.visible = state.show.visibleLinks && !selecting;
    layers.partialLinks.visible = state.show.partialLinks && !selecting;
    section.constant = state.sectionHeight;
    renderer.render(scene, camera);
    state.frames += 1;
  }

  function resize() {
    renderer.setSize(window.innerWidth, window.innerHeight);
    camera.aspect = window.innerWidth / Math.max(window.innerHeight, 1);
    camera.updateProjectionMatrix();
    render();
  }

  function setOverlay(group) {
    if (overlay) {
      scene.remove(overlay);
      overlay.traverse((o) => {
        if (o.geometry) o.geometry.dispose();
        if (o.material) o.material.dispose();
      });
    }
    overlay = group;
    if (overlay) scene.add(overlay);
  }

  function refreshSelection() {
    if (state.selectedPair !== null) {
      setOverlay(pairSelectionGroup(layers, pairs, pairs.find(...state.selectedPair), diagonal, [section]));
    } else if (state.selectedPatch !== null) {
      setOverlay(patchSelectionGroup(layers, pairs, state.selectedPatch, diagonal, [section]));
    } else {
      setOverlay(null);
    }
    panel.update();
    render();
  }

  const api = {
    render,
    /** Selects patch `p` (null clears the selection). */
    selectPatch(p) {
      if (p !== null && !(p >= 0 && p < patchCount)) throw new Error(`no patch ${p}`);
      state.selectedPatch = p;
      state.selectedPair = null;
      refreshSelection();
    },
    /** Selects the interaction of patches a and b; returns false if they do not interact. */
    selectPair(a, b) {
      const k = pairs.find(a, b);
      if (k < 0) return false;
      state.selectedPatch = a;
      state.selectedPair = [pairs.s[k], pairs.r[k]];
      refreshSelection();
      return true;
    },
    clearSelection() {
      api.selectPatch(null);
    },
    setShading(mode) {
      state.shading = mode;
      panel.update();
      render();
    },
    setLayer(name, on) {
      state.show[name] = on;
      panel.update();
      render();
    },
    setSectionHeight(z) {
      state.sectionHeight = z;
      panel.update();
      render();
    },
    resetView() {
      resetView();
      render();
    },
    /** The patch drawn at client pixel (x, y), or null: the first front face below the section. */
    patchAt(x, y) {
      const rect = renderer.domElement.getBoundingClientRect();
      const ndc = new THREE.Vector2(((x - rect.left) / rect.width) * 2 - 1, -((y - rect.top) / rect.height) * 2 + 1);
      const raycaster = new THREE.Raycaster();
      raycaster.setFromCamera(ndc, camera);
      for (const hit of raycaster.intersectObject(layers.pick, false)) {
        if (hit.point.getComponent(up) > state.sectionHeight) continue;
        return layers.pick.userData.polygonOfTriangle[hit.faceIndex];
      }
      return null;
    },
    /** How many patches patch p interacts with. */
    partnerCount(p) {
      return pairs.byPatch[p].length;
    },
    /** The patches patch p interacts with. */
    partnersOf(p) {
      return pairs.byPatch[p].map((k) => pairs.partnerOf(k, p));
    },
    /** A client pixel where a click picks patch p (tries points across it), or null. */
    screenPointOfPatch(p) {
      const rect = renderer.domElement.getBoundingClientRect();
      const poly = layers.patches[p];
      const c = layers.centroids[p];
      const candidates = [c];
      for (const v of poly) for (const t of [0.3, 0.6]) candidates.push(c.map((ci, i) => ci + t * (v[i] - ci)));
      for (const point of candidates) {
        const v = new THREE.Vector3(...point).project(camera);
        if (Math.abs(v.x) > 0.98 || Math.abs(v.y) > 0.98 || v.z > 1) continue;
        const x = rect.left + ((v.x + 1) / 2) * rect.width;
        const y = rect.top + ((1 - v.y) / 2) * rect.height;
        // The pixel must reach the canvas (not the panel above it) and show patch p.
        if (document.elementFromPoint(x, y) !== renderer.domElement) continue;
        if (api.patchAt(x, y) === p) return { x, y };
      }
      return null;
    },
  };
  window.viewerApi = api;

  const panel = createPanel(document, data, state, pairs, api);

  let down = null;
  renderer.domElement.addEventListener('pointerdown', (e) => {
    down = { x: e.clientX, y: e.clientY };
  });
  renderer.domElement.addEventListener('pointerup', (e) => {
    if (!down || Math.hypot(e.clientX - down.x, e.clientY - down.y) > CLICK_SLOP_PIXELS) return;
    down = null;
    const p = api.patchAt(e.clientX, e.clientY);
    if (p === null) {
      api.clearSelection();
    } else if (e.shiftKey && state.selectedPatch !== null && pairs.find(state.selectedPatch, p) >= 0) {
      api.selectPair(state.selectedPatch, p);
    } else {
      api.selectPatch(p);
    }
  });
  window.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') api.clearSelection();
  });
  controls.addEventListener('change', render);
  window.addEventListener('resize', resize);
  resize();
  state.ready = true;
}

try {
  start();
} catch (e) {
  const box = document.createElement('pre');
  box.className = 'gv-error';
  box.textContent = String(e && e.stack ? e.stack : e);
  document.body.appendChild(box);
  throw e;
}
