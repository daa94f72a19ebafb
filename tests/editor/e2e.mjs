// End-to-end test of `bspcsg edit` in headless Chromium (Debian's package), driven by
// playwright-core. .ci/extra-checks runs it after `cargo build --release`:
//
//   node tests/editor/e2e.mjs [--bin target/release/bspcsg] [--shots DIR]
//
// 1. On a scratch scene: add a box and a sphere, subtract, change the radius twice, undo once,
//    save; the saved JSON must be that scene.
// 2. The GPU preview of the saved scene must match `bspcsg render` of the file (CPU) within
//    the tolerance below.
// 3. Export (GLB, BSP route) must download a closed mesh; `check` must pass.
// 4. The mechanical example: preview frames per second at 800×600 in software GL, and the
//    server's bake (marching cubes) and BSP-route export times, which must be under 1 s.
// 5. Every example scene: its shader's frame against `bspcsg render` of the file.
//
// Pixel tolerance of step 2, in 8-bit sRGB levels over the 400×300 image: mean absolute
// difference per channel ≤ 2, and at most 1.5 % of pixels differing by more than 48 in any
// channel. The GPU marches in float32, the CPU in float64, so rays that graze a silhouette or an
// edge can land on the other side of it: those pixels differ a lot, but there are few of them.
import { spawn, execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, readdirSync, writeFileSync, copyFileSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { chromium } from 'playwright-core';

const args = process.argv.slice(2);
const opt = (name, dflt) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : dflt;
};
const bin = resolve(opt('--bin', 'target/release/bspcsg'));
const scratch = mkdtempSync(join(tmpdir(), 'bspcsg-editor-e2e-'));
const shots = resolve(opt('--shots', scratch));
mkdirSync(shots, { recursive: true });
const MEAN_LIMIT = 2;
const OUTLIER_LEVEL = 48;
const OUTLIER_LIMIT = 0.015;

// The whole test is bounded: a hung browser or server fails it instead of stalling CI.
const watchdog = setTimeout(() => {
  console.error('editor e2e: timed out after 150 s');
  process.exit(1);
}, 150_000);

const servers = [];
const errors = [];
function serve(scene) {
  return new Promise((ok, fail) => {
    const p = spawn(bin, ['edit', scene, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
    servers.push(p);
    let out = '';
    p.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) ok(m[0]);
    });
    p.on('exit', (code) => fail(new Error(`bspcsg edit exited with ${code}: ${out}`)));
  });
}

function check(cond, what) {
  if (!cond) throw new Error(`FAILED: ${what}`);
  console.log(`ok: ${what}`);
}

async function nextPreview(page, before) {
  await page.waitForFunction((n) => (window.editor.state.previews || 0) > n, before, { timeout: 30_000 });
}
const previews = (page) => page.evaluate(() => window.editor.state.previews || 0);

async function setField(page, selector, value) {
  const before = await previews(page);
  // Typing, then leaving the field (Tab) fires `change`, as for a user.
  await page.fill(selector, String(value));
  await page.press(selector, 'Tab');
  await nextPreview(page, before);
}

async function main() {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: [
      '--no-sandbox',
      // WebGL2 in software: SwiftShader behind ANGLE (there is no GPU here).
      '--use-gl=angle',
      '--use-angle=swiftshader',
      '--enable-unsafe-swiftshader',
      '--ignore-gpu-blocklist',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
      '--disable-quic',
      '--no-first-run',
      '--disable-default-apps',
    ],
  });
  try {
    await editScene(browser);
    await measureMechanical(browser);
  } finally {
    await browser.close();
  }
}

async function editScene(browser) {
  const scene = join(scratch, 'part.json');
  const url = await serve(scene);
  const page = await browser.newPage({ viewport: { width: 1500, height: 900 }, acceptDownloads: true });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(url);
  await page.waitForSelector('#tree');
  check(await page.evaluate(() => !!document.getElementById('preview').getContext('webgl2')), 'WebGL2 is available');

  let n = await previews(page);
  await page.click('#add-box');
  await nextPreview(page, n);
  n = await previews(page);
  await page.click('#add-sphere');
  await nextPreview(page, n);
  // The sphere went in after the box; mark both and subtract.
  await page.click('.node[data-path="$.tree.children[0]"]');
  await page.click('.node[data-path="$.tree.children[1]"]', { modifiers: ['Control'] });
  await page.selectOption('#group-op', 'subtract');
  n = await previews(page);
  await page.click('#group');
  await nextPreview(page, n);
  await page.click('.node[data-path="$.tree.children[0].children[1]"]');
  await setField(page, '#prop-pos input:nth-child(1)', 0.35);
  await setField(page, '#prop-pos input:nth-child(2)', 0.3);
  await setField(page, '#prop-radius', 0.7);
  await setField(page, '#prop-radius', 1.1);
  n = await previews(page);
  await page.click('#undo');
  await nextPreview(page, n);
  check((await page.inputValue('#prop-radius')) === '0.7', 'undo restored the radius field to 0.7');
  // The log lists every action; the undone ones are struck out.
  const log = await page.$$eval('#log li', (li) => li.map((l) => `${l.className}|${l.textContent}`));
  check(log.some((l) => l.startsWith('undone|') && l.includes('radius = 1.1')), 'the log shows the undone radius change');
  // The properties panel shows the server's JSON-path message for a bad value.
  await page.fill('#prop-radius', '-1');
  await page.press('#prop-radius', 'Tab');
  await page.waitForFunction(() => /radius/.test(document.getElementById('message').textContent));
  const message = await page.textContent('#message');
  check(message.includes('$.tree.children[0].children[1].data.radius'), `validation message names the JSON path: ${message}`);
  n = await previews(page);
  await page.click('#undo');
  await nextPreview(page, n);

  await page.click('#save');
  await page.waitForFunction(() => /saved/.test(document.getElementById('message').textContent));
  const saved = JSON.parse(readFileSync(scene, 'utf8'));
  check((await page.textContent('#log')).includes('saved part.json'), 'the log records the save');
  const sub = saved.tree.children[0];
  check(saved.tree.op === 'union' && saved.tree.children.length === 1, 'saved: one node under the root union');
  check(sub.op === 'subtract' && sub.children.length === 2, 'saved: a subtraction of two nodes');
  check(sub.children[0].data.primitive_type === 'box' && sub.children[0].data.size.join() === '1,1,1', 'saved: the box first');
  check(sub.children[1].data.primitive_type === 'sphere' && sub.children[1].data.radius === 0.7, 'saved: the sphere, radius 0.7 after the undo');
  check(sub.children[1].pos.join() === '0.35,0.3,0', 'saved: the sphere moved to (0.35, 0.3, 0)');


  // GPU preview against the CPU render of the saved file, same size, same default framing.
  n = await previews(page);
  await page.selectOption('#preview-size', '400x300');
  await nextPreview(page, n);
  await page.evaluate(() => {
    window.editor.state.selected = null;
    window.editor.preview.selection = [-1, -1];
    window.editor.preview.frame();
  });
  const cmp = await compareWithCpu(page, scene, join(shots, 'editor-cpu.png'));
  writeFileSync(join(shots, 'editor-gpu.png'), Buffer.from(cmp.gpu.split(',')[1], 'base64'));
  console.log(`preview vs CPU render: mean |diff| ${cmp.mean.toFixed(3)} levels, ${(100 * cmp.outliers).toFixed(3)} % pixels > ${OUTLIER_LEVEL}, object covers ${(100 * cmp.covered).toFixed(1)} %`);
  check(cmp.covered > 0.05, 'the CPU render shows the part');
  check(cmp.mean <= MEAN_LIMIT && cmp.outliers <= OUTLIER_LIMIT, 'the GPU preview matches the CPU render within tolerance');
  await exportAndCheck(page);
  await page.close();
}

// The canvas (400×300) against `bspcsg render SCENE --size 400x300`.
async function compareWithCpu(page, scene, cpuPng) {
  execFileSync(bin, ['--quiet', 'render', scene, '-o', cpuPng, '--size', '400x300']);
  return page.evaluate(async (cpu) => {
    const img = new Image();
    img.src = `data:image/png;base64,${cpu}`;
    await img.decode();
    const w = 400, h = 300;
    const read = (src) => {
      const c = document.createElement('canvas');
      c.width = w;
      c.height = h;
      const g = c.getContext('2d');
      g.drawImage(src, 0, 0);
      return g.getImageData(0, 0, w, h).data;
    };
    const a = read(document.getElementById('preview'));
    const b = read(img);
    let sum = 0, outliers = 0, hit = 0;
    const bg = [b[0], b[1], b[2]];
    for (let i = 0; i < a.length; i += 4) {
      let m = 0;
      for (let k = 0; k < 3; k++) {
        const d = Math.abs(a[i + k] - b[i + k]);
        sum += d;
        m = Math.max(m, d);
      }
      if (m > 48) outliers++;
      if (b[i] !== bg[0] || b[i + 1] !== bg[1] || b[i + 2] !== bg[2]) hit++;
    }
    return { mean: sum / (w * h * 3), outliers: outliers / (w * h), covered: hit / (w * h), gpu: document.getElementById('preview').toDataURL('image/png') };
  }, readFileSync(cpuPng).toString('base64'));
}

async function exportAndCheck(page) {
  // Export: a GLB by the BSP route, downloaded, closed.
  await page.selectOption('#export-format', 'glb');
  await page.selectOption('#export-via', 'bsp');
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export')]);
  const glb = readFileSync(await download.path());
  check(glb.subarray(0, 4).toString() === 'glTF', `export downloaded ${download.suggestedFilename()} (${glb.length} bytes of GLB)`);
  const report = await page.textContent('#report');
  check(/closed manifold/.test(report) && !/NOT/.test(report), `export report: ${report}`);
  await page.click('#check');
  await page.waitForFunction(() => /^check \(/.test(document.getElementById('report').textContent), null, { timeout: 60_000 });
  const checked = await page.textContent('#report');
  check(/PASS/.test(checked), `check: ${checked.split('\n')[0]}`);

  // The mesh view: the server's mesh with its report.
  await page.selectOption('#view-mode', 'mesh');
  await page.waitForFunction(() => /triangles/.test(document.getElementById('mesh-info').textContent), null, { timeout: 30_000 });
  const meshInfo = await page.textContent('#mesh-info');
  check(/closed manifold/.test(meshInfo), `mesh view: ${meshInfo}`);
  await page.screenshot({ path: join(shots, 'editor-mesh.png') });
  await page.selectOption('#view-mode', 'preview');

  // Selecting the sphere tints its leaf: the frame changes where the sphere decides the surface.
  const tinted = await page.evaluate(async () => {
    const gl = window.editor.preview.gl;
    const grab = () => {
      window.editor.preview.frame();
      const px = new Uint8Array(400 * 300 * 4);
      gl.readPixels(0, 0, 400, 300, gl.RGBA, gl.UNSIGNED_BYTE, px);
      return px;
    };
    window.editor.preview.selection = [-1, -1];
    const plain = grab();
    window.editor.preview.selection = [1, 2];
    const lit = grab();
    let changed = 0, orange = 0;
    for (let i = 0; i < plain.length; i += 4) {
      if (plain[i] !== lit[i] || plain[i + 1] !== lit[i + 1] || plain[i + 2] !== lit[i + 2]) {
        changed++;
        if (lit[i] > lit[i + 2]) orange++;
      }
    }
    return { changed: changed / (400 * 300), orange };
  });
  check(tinted.changed > 0.02 && tinted.orange > 0.9 * tinted.changed * 400 * 300, `the selected sphere is highlighted (${(100 * tinted.changed).toFixed(1)} % of pixels tinted)`);
  await page.click('.node[data-path="$.tree.children[0].children[1]"]');
  const leaves = await page.evaluate(() => window.editor.preview.selection);
  check(leaves[0] === 1 && leaves[1] === 2, 'clicking the sphere selects its leaf (1) in the shader');

  // A picture of the editor with the sphere selected (highlighted), for the README.
  await page.selectOption('#preview-size', 'fit');
  await page.waitForTimeout(300);
  await page.screenshot({ path: join(shots, 'editor.png') });
}

async function measureMechanical(browser) {
  const scene = join(scratch, 'mechanical_part.json');
  copyFileSync('examples/scenes/mechanical_part.json', scene);
  const url = await serve(scene);
  const page = await browser.newPage({ viewport: { width: 1500, height: 900 } });
  await page.goto(url);
  await page.waitForFunction(() => (window.editor.state.previews || 0) > 0, null, { timeout: 30_000 });
  const n = await previews(page);
  await page.selectOption('#preview-size', '800x600');
  await nextPreview(page, n);
  // Frames with and without the bounding-sphere skipping of primitives, alternating, so that
  // the machine's load weighs on both alike.
  const shaderWith = async (cull) => page.evaluate(async (cull) => {
    const doc = window.editor.state.doc;
    const r = await fetch(`/api/shader?w=800&h=600${cull ? '&cull=1' : ''}`, {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(doc),
    });
    window.editor.preview.setShader((await r.json()).glsl);
  }, cull);
  const times = { true: [], false: [] };
  for (let round = 0; round < 3; round++) {
    for (const cull of [true, false]) {
      await shaderWith(cull);
      times[cull].push((await page.evaluate(() => window.editor.measureFps(4))).ms_per_frame);
    }
  }
  const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
  const fps = { fps: 1000 / median(times.false), width: 800, height: 600 };
  await shaderWith(false);
  const drag = await page.evaluate(() => window.editor.measureFps(4, 0.5));
  console.log(`mechanical_part preview at 800×600 in software GL: ${fps.fps.toFixed(2)} fps (median ${median(times.false).toFixed(0)} ms a frame; ${median(times.true).toFixed(0)} ms skipping primitives by bounding spheres); while dragging (half resolution, scaled up) ${drag.fps.toFixed(2)} fps`);
  check(fps.fps >= 1, 'the preview renders at least one frame a second in software GL');
  await page.screenshot({ path: join(shots, 'editor-mechanical.png') });

  // Every example scene: the shader generated from it against the CPU render of its file (their
  // cameras, lights, materials, rotations, smooth blends, extrusions and revolutions).
  const before = await previews(page);
  await page.selectOption('#preview-size', '400x300');
  await nextPreview(page, before);
  for (const name of readdirSync('examples/scenes').filter((f) => f.endsWith('.json')).sort()) {
    const file = join('examples/scenes', name);
    await page.evaluate(async (doc) => {
      const r = await fetch('/api/shader?w=400&h=300', {
        method: 'POST', headers: { 'Content-Type': 'application/json' }, body: doc,
      });
      const body = await r.json();
      window.editor.state.autoFrame = false;
      window.editor.setCamera(body.camera);
      window.editor.preview.selection = [-1, -1];
      window.editor.preview.setShader(body.glsl);
      window.editor.preview.frame();
    }, readFileSync(file, 'utf8'));
    const cmp = await compareWithCpu(page, file, join(shots, `example-cpu-${name}.png`));
    writeFileSync(join(shots, `example-gpu-${name}.png`), Buffer.from(cmp.gpu.split(',')[1], 'base64'));
    console.log(`${name}: preview vs CPU render: mean |diff| ${cmp.mean.toFixed(3)} levels, ${(100 * cmp.outliers).toFixed(3)} % pixels > ${OUTLIER_LEVEL}`);
    check(cmp.covered > 0.05 && cmp.mean <= MEAN_LIMIT && cmp.outliers <= OUTLIER_LIMIT, `${name}: the GPU preview matches the CPU render within tolerance`);
  }
  check(errors.length === 0, `no page errors ${errors.join('; ')}`);
  const document = JSON.parse(readFileSync(scene, 'utf8'));
  for (const via of ['sdf', 'bsp']) {
    const t0 = performance.now();
    const r = await fetch(`${url}api/export`, {
      method: 'POST',
      headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify({ document, format: 'glb', via }),
    });
    const bytes = await r.arrayBuffer();
    const ms = performance.now() - t0;
    const rep = JSON.parse(r.headers.get('x-bspcsg-report'));
    console.log(`mechanical_part export by ${via}: ${rep.triangles} triangles, closed ${rep.closed_manifold}, meshing ${(rep.seconds * 1000).toFixed(0)} ms, request ${ms.toFixed(0)} ms, ${bytes.byteLength} bytes`);
    check(r.ok && rep.closed_manifold, `export by ${via} is a closed mesh`);
    if (via === 'sdf') check(ms < 1000, 'the server answers a bake of the mechanical example in under 1 s');
  }
  await page.close();
}

main()
  .then(() => {
    console.log('editor e2e: passed');
  })
  .catch((e) => {
    console.error(e.stack || String(e));
    process.exitCode = 1;
  })
  .finally(() => {
    for (const s of servers) s.kill();
    clearTimeout(watchdog);
    // The scratch folder goes, except after a failure when it holds the pictures.
    if (process.exitCode && shots === scratch) console.error(`pictures kept in ${scratch}`);
    else rmSync(scratch, { recursive: true, force: true });
  });
