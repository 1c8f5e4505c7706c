// The viewer's control panel: shading, layer toggles, section height, and the selection (a
// patch's interactions as a list; one interaction's blockers).

/** Blocker ids printed for a selected interaction (all of them are drawn). */
const MAX_LISTED_BLOCKERS = 30;

const STYLE = `
html, body { margin: 0; height: 100%; overflow: hidden; background: #1e2226; }
body { font: 13px/1.35 system-ui, sans-serif; color: #e8e8e8; }
#gv-canvas { position: absolute; inset: 0; display: block; }
.gv-panel { position: absolute; top: 8px; left: 8px; width: 300px; max-height: calc(100% - 16px);
  overflow: auto; background: rgba(20, 22, 26, 0.88); border: 1px solid #444; border-radius: 6px;
  padding: 8px 10px; box-sizing: border-box; }
.gv-panel h1 { font-size: 15px; margin: 0 0 4px; }
.gv-panel h2 { font-size: 13px; margin: 10px 0 4px; color: #bbb; }
.gv-panel label { display: block; margin: 2px 0; }
.gv-panel .gv-muted { color: #999; }
.gv-panel ul { list-style: none; margin: 4px 0; padding: 0; max-height: 220px; overflow: auto; }
.gv-panel li { padding: 1px 4px; cursor: pointer; border-radius: 3px; }
.gv-panel li:hover { background: #333a44; }
.gv-panel li.gv-current { background: #5a4a10; }
.gv-sources { white-space: pre-wrap; word-break: break-all; font-size: 11px; }
.gv-swatch { display: inline-block; width: 10px; height: 10px; margin-right: 4px; border: 1px solid #000; }
.gv-error { position: absolute; bottom: 0; left: 0; right: 0; color: #f66; background: #200; margin: 0; padding: 8px; }
button { font: inherit; }
`;

function el(doc, tag, attrs = {}, children = []) {
  const e = doc.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'text') e.textContent = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.appendChild(c);
  return e;
}

function swatch(doc, color) {
  return el(doc, 'span', { class: 'gv-swatch', style: `background:#${color.toString(16).padStart(6, '0')}` });
}

/** Builds the panel into `doc.body`; returns {update()} to redraw it from `state`. */
export function createPanel(doc, data, state, pairs, api) {
  doc.head.appendChild(el(doc, 'style', { text: STYLE }));
  const panel = el(doc, 'div', { class: 'gv-panel', id: 'gv-panel' });
  doc.body.appendChild(panel);

  const visibleCount = Array.from({ length: pairs.count }, (_, k) => pairs.isVisible(k)).filter(Boolean).length;
  panel.appendChild(el(doc, 'h1', { text: data.title || 'globalvis viewer' }));
  panel.appendChild(
    el(doc, 'div', {
      class: 'gv-muted',
      text:
        `${state.patchCount} patches, ${pairs.count} interacting pairs ` +
        `(${visibleCount} VISIBLE, ${pairs.count - visibleCount} PARTIAL)` +
        (data.cells ? `, ${data.cellCount} cells` : '') +
        (data.portals ? `, ${data.portals.cells.length / 2} portals` : ''),
    }),
  );

  const sources = Object.entries(data.sources || {}).map(([k, v]) => `${k}: ${v}`);
  panel.appendChild(el(doc, 'details', {}, [
    el(doc, 'summary', { class: 'gv-muted', text: 'files' }),
    el(doc, 'div', { class: 'gv-muted gv-sources', text: [...sources, ...(data.notes || [])].join('\n') }),
  ]));

  panel.appendChild(el(doc, 'h2', { text: 'Show' }));
  const checkbox = (name, label, color, enabled) => {
    const input = el(doc, 'input', { type: 'checkbox', id: `gv-toggle-${name}` });
    input.disabled = !enabled;
    input.addEventListener('change', () => api.setLayer(name, input.checked));
    panel.appendChild(el(doc, 'label', {}, [input, swatch(doc, color), doc.createTextNode(label + (enabled ? '' : ' (no data)'))]));
    return input;
  };
  const toggles = {
    cells: checkbox('cells', 'cells', 0x4aa3ff, !!data.cells),
    portals: checkbox('portals', 'portals', 0xff40ff, !!data.portals),
    visibleLinks: checkbox('visibleLinks', 'VISIBLE links', 0xffffff, pairs.count > 0),
    partialLinks: checkbox('partialLinks', 'PARTIAL links', 0x22dd22, pairs.count > 0),
  };

  const shading = el(doc, 'select', { id: 'gv-shading' });
  shading.appendChild(el(doc, 'option', { value: 'radiosity', text: 'radiosity' }));
  shading.appendChild(el(doc, 'option', { value: 'material', text: 'material colour' }));
  shading.disabled = !(data.elements || data.radiosity);
  shading.addEventListener('change', () => api.setShading(shading.value));
  panel.appendChild(el(doc, 'label', {}, [doc.createTextNode('shading '), shading]));

  const lo = data.bounds.min[state.upAxis];
  const hi = data.bounds.max[state.upAxis];
  const slider = el(doc, 'input', { type: 'range', min: '0', max: '1000', id: 'gv-section' });
  slider.addEventListener('input', () => api.setSectionHeight(lo + (hi - lo) * (slider.value / 1000) * 1.001));
  panel.appendChild(el(doc, 'label', {}, [doc.createTextNode('cut away above '), slider]));
  panel.appendChild(
    el(doc, 'div', {}, [
      el(doc, 'button', { text: 'reset view', onclick: () => api.resetView() }),
      doc.createTextNode(' '),
      el(doc, 'button', { text: 'clear selection', onclick: () => api.clearSelection() }),
    ]),
  );
  panel.appendChild(
    el(doc, 'div', {
      class: 'gv-muted',
      text: 'Drag to orbit, right-drag to pan, wheel to zoom. Click a patch (yellow) to see what it ' +
        'sees (VISIBLE white, PARTIAL green); shift-click one of its partners, or pick one below, ' +
        'for the interaction (receiver cyan): its tube (red) and blockers (orange). Esc clears.',
    }),
  );

  const selection = el(doc, 'div', { id: 'gv-selection' });
  panel.appendChild(el(doc, 'h2', { text: 'Selection' }));
  panel.appendChild(selection);

  const materialName = (p) => (data.materials[data.patches.material[p]] || {}).name || '?';
  function describeSelection() {
    selection.replaceChildren();
    const p = state.selectedPatch;
    if (p === null) {
      selection.appendChild(el(doc, 'div', { class: 'gv-muted', text: 'nothing selected' }));
      return;
    }
    const ks = pairs.byPatch[p];
    const partial = ks.filter((k) => !pairs.isVisible(k)).length;
    selection.appendChild(swatch(doc, 0xffee00));
    selection.appendChild(
      doc.createTextNode(`patch ${p} (${materialName(p)}) sees ${ks.length} patches: ${ks.length - partial} VISIBLE, ${partial} PARTIAL`),
    );
    if (state.selectedPair) {
      const [s, r] = state.selectedPair;
      const k = pairs.find(s, r);
      const blockers = pairs.blockersOf(k);
      const n = pairs.blockerCount(k);
      const shown = pairs.blockersEmbedded ? 'orange' : 'not embedded in this page';
      selection.appendChild(
        el(doc, 'div', { id: 'gv-pair' }, [
          swatch(doc, 0xff2020),
          doc.createTextNode(
            `interaction ${s}-${r}: ${n ? `PARTIAL, ${n} blockers (${shown})` : 'VISIBLE'}` +
              (blockers.length ? `: ${blockers.slice(0, MAX_LISTED_BLOCKERS).join(' ')}` : '') +
              (blockers.length > MAX_LISTED_BLOCKERS ? ' …' : ''),
          ),
        ]),
      );
    }
    const list = el(doc, 'ul', { id: 'gv-partners' });
    const sorted = [...ks].sort((a, b) => pairs.blockerCount(b) - pairs.blockerCount(a));
    for (const k of sorted) {
      const q = pairs.partnerOf(k, p);
      const n = pairs.blockerCount(k);
      const current = state.selectedPair && pairs.find(...state.selectedPair) === k;
      list.appendChild(
        el(doc, 'li', { class: current ? 'gv-current' : '', 'data-partner': String(q), onclick: () => api.selectPair(p, q) }, [
          swatch(doc, n ? 0x22dd22 : 0xffffff),
          doc.createTextNode(`${q} (${materialName(q)}): ${n ? `PARTIAL, ${n} blockers` : 'VISIBLE'}`),
        ]),
      );
    }
    selection.appendChild(list);
  }

  function update() {
    for (const [name, input] of Object.entries(toggles)) input.checked = state.show[name];
    shading.value = state.shading;
    slider.value = String(Math.round(((state.sectionHeight - lo) / ((hi - lo) * 1.001 || 1)) * 1000));
    describeSelection();
  }
  update();
  return { update };
}
