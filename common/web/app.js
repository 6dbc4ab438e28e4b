// app.js - the page of make web: choose a scene and a stage (or two), render
// with the stage's own main() spread over Web Workers (worker.js), show the
// passes as they finish, and inspect, compare and download the result.
//
// Each worker renders every pass of its share of the tiles (web_main.c) and
// posts the mean of its passes so far; the tiles of the other workers are 0
// in its image, so the sum of the workers' latest images is the picture, and
// once every worker is done it is the native build's image (same code, same
// per-pixel random streams).  Nothing here computes light: the display's
// exposure and tone map, the error map against a reference and the merged
// statistics are the only arithmetic on the page.
'use strict';

const $ = (id) => document.getElementById(id);

const page = {
    library: null, // library.json (bundle.sh)
    scene: null, // {path, data (string or ArrayBuffer), needs: [paths]}
    files: {}, // path -> contents, fetched once
    panels: [],
    helpCache: {},
};

async function fetchFile(path, asText) {
    if (!(path in page.files)) {
        const response = await fetch(path);
        if (!response.ok) {
            throw new Error(path + ': ' + response.status + ' ' + response.statusText);
        }
        page.files[path] = asText ? await response.text() : await response.arrayBuffer();
    }
    return page.files[path];
}

// A request to a worker; resolves with its 'done' answer, or with status
// 'stopped' when worker.stop() ends it.  onMessage gets the messages before
// it (passes, log lines).
let nextId = 1;
function ask(worker, request, onMessage) {
    const id = nextId++;
    return new Promise((resolve) => {
        worker.stop = () => {
            worker.terminate();
            resolve({type: 'done', id, status: 'stopped'});
        };
        worker.onmessage = (event) => {
            const m = event.data;
            if (m.id !== id) {
                return;
            }
            if (m.type === 'done') {
                resolve(m);
            } else if (onMessage) {
                onMessage(m);
            }
        };
        worker.postMessage(Object.assign({id}, request));
    });
}

// --- the scene -----------------------------------------------------------

async function chooseLibraryScene(name) {
    const entry = page.library.scenes.find((s) => s.name === name);
    const text = entry.file.endsWith('.glb') ? null : await fetchFile(entry.file, true);
    page.scene = {path: entry.file, data: text, needs: entry.needs, references: entry.references};
    $('scene-text').value = text || '';
    for (const panel of page.panels) {
        panel.showReferences();
    }
}

// The scene as the user has it now: the library's, edited or pasted.
function currentScene() {
    const scene = Object.assign({}, page.scene);
    const edited = $('scene-text').value;
    if (typeof scene.data === 'string' && edited !== scene.data) {
        scene.data = edited;
    }
    return scene;
}

// The models a scene's text names (mesh file WORD or "WORD", comments
// left out), as paths of the page's files: scenes/WORD.
function namedModels(text) {
    const names = [];
    for (const line of text.split('\n')) {
        const m = /\bfile\s+(?:"([^"]*)"|(\S+))/.exec(line.replace(/#.*/, ''));
        if (m) names.push('scenes/' + (m[1] || m[2]));
    }
    return names;
}

// The files of a render: the scene, the models it names that the library
// bundles or the user uploaded beside it (the others: the stage's own
// "cannot load mesh" error).
async function sceneFiles(scene) {
    const files = {};
    files[scene.path] = scene.data;
    const bundled = new Set(page.library.scenes.flatMap((s) => s.needs));
    const named = typeof scene.data === 'string' ? namedModels(scene.data) : [];
    for (const need of new Set(scene.needs.concat(named))) {
        if (page.uploads[need]) {
            files[need] = page.uploads[need];
        } else if (bundled.has(need)) {
            files[need] = await fetchFile(need, false);
        }
    }
    return files;
}

// Files uploaded beside the scene (its models), by their page path.
page.uploads = {};

function uploadModel(file) {
    const reader = new FileReader();
    reader.onload = () => {
        page.uploads['scenes/' + file.name] = reader.result;
        page.uploads['scenes/models/' + file.name] = reader.result;
    };
    reader.readAsArrayBuffer(file);
}

function uploadScene(file) {
    const reader = new FileReader();
    const binary = file.name.endsWith('.glb');
    reader.onload = () => {
        const safe = file.name.replace(/[^A-Za-z0-9_.-]/g, '_');
        page.scene = {path: 'scenes/' + safe, data: reader.result, needs: [], references: []};
        $('scene-text').value = binary ? '' : reader.result;
        $('scene-details').open = !binary;
        for (const panel of page.panels) {
            panel.showReferences();
        }
    };
    if (binary) {
        reader.readAsArrayBuffer(file);
    } else {
        reader.readAsText(file);
    }
}

// --- display -------------------------------------------------------------

const tonemaps = {
    clamp: (x) => x,
    reinhard: (x) => x / (1 + x),
    aces: (x) => (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14),
};

// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1], to 8 bits.
function srgb8(v) {
    v = v <= 0 ? 0 : v >= 1 ? 1 : v;
    const s = v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
    return Math.round(s * 255);
}

function drawImage(canvas, rgb, width, height) {
    const scale = Math.pow(2, Number($('exposure').value));
    const map = tonemaps[$('tonemap').value];
    canvas.width = width;
    canvas.height = height;
    const ctx = canvas.getContext('2d');
    const out = ctx.createImageData(width, height);
    for (let i = 0, n = width * height; i < n; i++) {
        for (let c = 0; c < 3; c++) {
            out.data[4 * i + c] = srgb8(map(rgb[3 * i + c] * scale));
        }
        out.data[4 * i + 3] = 255;
    }
    ctx.putImageData(out, 0, 0);
}

// An empty panel's canvas: what to do, not a black square (a page that
// rendered on load would start minutes of work nobody asked for).
function drawPrompt(canvas, lines) {
    canvas.width = 512;
    canvas.height = 256;
    const ctx = canvas.getContext('2d');
    ctx.fillStyle = '#222';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.fillStyle = '#ddd';
    ctx.font = '20px sans-serif';
    ctx.textAlign = 'center';
    lines.forEach((line, i) => ctx.fillText(line, canvas.width / 2, canvas.height / 2 + (i - (lines.length - 1) / 2) * 30));
}

// A PFM file's floats, rows top to bottom (the file stores them bottom to top).
function parsePfm(buffer) {
    const bytes = new Uint8Array(buffer);
    let pos = 0;
    const token = () => {
        while (/\s/.test(String.fromCharCode(bytes[pos]))) pos++;
        let t = '';
        while (pos < bytes.length && !/\s/.test(String.fromCharCode(bytes[pos]))) t += String.fromCharCode(bytes[pos++]);
        return t;
    };
    const magic = token();
    const width = Number(token());
    const height = Number(token());
    const scale = Number(token());
    pos++;
    if (magic !== 'PF' || !(width > 0) || !(height > 0)) {
        throw new Error('not a colour PFM file');
    }
    const view = new DataView(buffer, pos);
    const little = scale < 0;
    const rgb = new Float32Array(width * height * 3);
    for (let y = 0; y < height; y++) {
        for (let i = 0; i < width * 3; i++) {
            rgb[y * width * 3 + i] = view.getFloat32(4 * ((height - 1 - y) * width * 3 + i), little);
        }
    }
    return {width, height, rgb};
}

// The error map of compare (tests/lib/errmap.h): per pixel the signed
// relative error of luminance e = (L - L_ref) / sqrt(L_ref^2 + 0.01), blue
// where darker, red where brighter, saturating at +-0.5 (RdBu ends); and
// relMSE (tests/lib/metrics.h) over all pixels and channels.
function drawErrorMap(canvas, rgb, ref) {
    const {width, height} = ref;
    canvas.width = width;
    canvas.height = height;
    const ctx = canvas.getContext('2d');
    const out = ctx.createImageData(width, height);
    const lum = (a, i) => 0.2126 * a[3 * i] + 0.7152 * a[3 * i + 1] + 0.0722 * a[3 * i + 2];
    let relmse = 0;
    for (let i = 0, n = width * height; i < n; i++) {
        const r = lum(ref.rgb, i);
        const e = (lum(rgb, i) - r) / Math.sqrt(r * r + 0.01);
        const t = Math.max(-1, Math.min(1, e / 0.5));
        const blue = [5, 48, 97];
        const red = [103, 0, 31];
        const end = t < 0 ? blue : red;
        const a = Math.abs(t);
        for (let c = 0; c < 3; c++) {
            out.data[4 * i + c] = Math.round(247 * (1 - a) + end[c] * a);
            const d = rgb[3 * i + c] - ref.rgb[3 * i + c];
            relmse += (d * d) / (ref.rgb[3 * i + c] * ref.rgb[3 * i + c] + 0.01);
        }
        out.data[4 * i + 3] = 255;
    }
    ctx.putImageData(out, 0, 0);
    return relmse / (3 * width * height);
}

// --- statistics ----------------------------------------------------------

// The workers' --stats objects as one: counts added, wall-clock times the
// longest, processor time added; rays_per_second again from the sums.
function mergeStats(list) {
    const merged = Object.assign({}, list[0]);
    const added = /^(rays_|prim_tests|node_visits|nan_pixels|seconds_render_cpu|.*_pixels$)/;
    for (const key of Object.keys(merged)) {
        if (typeof merged[key] !== 'number' || key === 'rays_per_second') continue;
        const values = list.map((s) => s[key]);
        if (added.test(key)) {
            merged[key] = values.reduce((a, b) => a + b, 0);
        } else if (key.startsWith('seconds_')) {
            merged[key] = Math.max(...values);
        }
    }
    const rays = merged.rays_camera + merged.rays_shadow + merged.rays_secondary;
    merged.rays_per_second = merged.seconds_render > 0 ? rays / merged.seconds_render : 0;
    merged.threads = list.length;
    merged.web_workers = list.length;
    return merged;
}

function download(name, bytes, type) {
    const url = URL.createObjectURL(new Blob([bytes], {type}));
    const a = document.createElement('a');
    a.href = url;
    a.download = name;
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// --- a panel: one stage's render -----------------------------------------

class Panel {
    constructor(index) {
        this.index = index;
        this.root = $('panel-template').content.firstElementChild.cloneNode(true);
        $('panels').appendChild(this.root);
        this.q = (sel) => this.root.querySelector(sel);
        this.workers = [];
        this.result = null; // {rgb, width, height, stats, args, scene, files}
        const select = this.q('.stage');
        for (const stage of page.library.stages) {
            select.add(new Option(stage, stage));
        }
        select.value = page.library.stages[index === 0 ? 0 : page.library.stages.length - 1];
        select.onchange = () => this.loadOptions();
        this.q('.image').onclick = (event) => this.inspect(event);
        this.q('.reference-file').onchange = () => this.drawReference();
        for (const button of this.root.querySelectorAll('.downloads button')) {
            button.onclick = () => this.download(button.dataset.format);
        }
        this.loadOptions();
    }

    get stage() {
        return this.q('.stage').value;
    }

    // The stage's own options, from its --help (the part after "options of
    // this stage:"): a box for each option with a value, a tick for a flag.
    async loadOptions() {
        const stage = this.stage;
        if (!page.helpCache[stage]) {
            const worker = new Worker('worker.js');
            page.helpCache[stage] = (await ask(worker, {type: 'help', stage})).text || '';
            worker.terminate();
        }
        const list = this.q('.option-list');
        list.textContent = '';
        const own = page.helpCache[stage].split('options of this stage:')[1] || '';
        for (const line of own.split('\n')) {
            const m = /^\s+(?:-\w, )?--([a-z0-9-]+)(?: (\S+))?\s+(.*)$/.exec(line);
            if (!m) continue;
            const label = document.createElement('label');
            label.textContent = '--' + m[1];
            const input = document.createElement('input');
            input.dataset.option = m[1];
            if (m[2]) {
                input.type = 'text';
                input.placeholder = m[2];
                input.size = 10;
            } else {
                input.type = 'checkbox';
            }
            label.appendChild(input);
            const help = document.createElement('span');
            help.className = 'help';
            help.textContent = m[3];
            list.append(label, help);
        }
        this.showReferences();
        this.redraw();
    }

    // The command line of this panel: the shared settings, then the stage's.
    args() {
        const args = [];
        const value = (id, flag) => {
            const v = $(id).value.trim();
            if (v !== '') args.push(flag, v);
        };
        value('width', '-W');
        value('height', '-H');
        value('spp', '--spp');
        value('seed', '--seed');
        for (const input of this.root.querySelectorAll('.option-list input')) {
            if (input.type === 'checkbox' && input.checked) {
                args.push('--' + input.dataset.option);
            } else if (input.type === 'text' && input.value.trim() !== '') {
                args.push('--' + input.dataset.option, input.value.trim());
            }
        }
        return args;
    }

    stop() {
        for (const w of this.workers) w.stop ? w.stop() : w.terminate();
        this.workers = [];
    }

    setStatus(text) {
        this.q('.status').textContent = text;
    }

    // What the stage printed on stderr (the first worker's: every worker
    // prints the same): errors in red, the "not modelled" warnings listed.
    showLog(lines) {
        const errors = lines.filter((l) => /(^|: )error: /.test(l) || /^(interrupted|usage)/.test(l));
        const warnings = lines.filter((l) => /: warning: /.test(l));
        const pre = this.q('.errors');
        pre.hidden = errors.length === 0;
        pre.textContent = errors.join('\n');
        const box = this.q('.warnings');
        box.hidden = warnings.length === 0;
        const ul = box.querySelector('ul');
        ul.textContent = '';
        for (const w of warnings) {
            const li = document.createElement('li');
            li.textContent = w;
            ul.appendChild(li);
        }
    }

    async render(scene, files, nWorkers) {
        this.stop();
        this.result = null;
        for (const b of this.root.querySelectorAll('.downloads button')) b.disabled = true;
        const args = this.args();
        const stage = this.stage;
        const start = performance.now();
        const latest = new Array(nWorkers).fill(null);
        const passes = new Array(nWorkers).fill(0);
        const log = [];
        let size = null;
        const compose = () => {
            const rgb = new Float32Array(size.width * size.height * 3);
            for (const part of latest) {
                if (!part) continue;
                for (let i = 0; i < rgb.length; i++) rgb[i] += part[i];
            }
            return rgb;
        };
        this.showLog([]);
        // No BVH before 05_bvh: every triangle is tested for every ray.
        const meshes = scene.needs.length > 0 || /\.gl(b|tf)$/.test(scene.path);
        const slow = meshes && stage < '05' ? ' (no BVH before 05_bvh: a mesh scene takes minutes at full size here; try a width of 64)' : '';
        this.setStatus('starting ' + nWorkers + ' workers...' + slow);
        const runs = [];
        for (let part = 0; part < nWorkers; part++) {
            const worker = new Worker('worker.js');
            this.workers.push(worker);
            const request = {type: 'render', stage, args, scene: scene.path, files, part, parts: nWorkers};
            runs.push(ask(worker, request, (m) => {
                if (m.type === 'log' && part === 0) {
                    log.push(m.line);
                    this.showLog(log);
                } else if (m.type === 'pass') {
                    latest[part] = m.rgb;
                    passes[part] = m.passes;
                    size = {width: m.width, height: m.height};
                    this.rgb = compose();
                    this.size = size;
                    drawImage(this.q('.image'), this.rgb, size.width, size.height);
                    const secs = ((performance.now() - start) / 1000).toFixed(1);
                    this.setStatus(`passes done: ${Math.min(...passes)} (every tile) to ${Math.max(...passes)}, ${secs} s${slow}`);
                }
            }));
        }
        const answers = await Promise.all(runs);
        this.stop();
        const seconds = (performance.now() - start) / 1000;
        const failed = answers.find((a) => a.status !== 0);
        if (failed && failed.status === 'stopped') {
            this.setStatus(`${stage}: stopped after ${seconds.toFixed(1)} s, ${Math.min(...passes)} complete passes shown`);
            return {status: failed.status, log};
        }
        if (failed) {
            if (failed.failure) log.push('error: ' + failed.failure);
            this.showLog(log);
            this.setStatus(`${stage} exited with status ${failed.status}`);
            return {status: failed.status, log};
        }
        const stats = mergeStats(answers.map((a) => JSON.parse(a.stats)));
        this.result = {rgb: this.rgb, width: size.width, height: size.height, stats, args, scene, files, stage};
        this.q('.stats').textContent = JSON.stringify(stats, null, 1);
        const mrays = (stats.rays_per_second / 1e6).toFixed(2);
        this.setStatus(`${stage}: ${stats.width}x${stats.height}, ${stats.spp} spp in ${seconds.toFixed(2)} s on ${nWorkers} workers, ${mrays} Mrays/s`);
        for (const b of this.root.querySelectorAll('.downloads button')) b.disabled = false;
        this.showReferences();
        return {status: 0, log, stats};
    }

    redraw() {
        if (this.rgb) drawImage(this.q('.image'), this.rgb, this.size.width, this.size.height);
        else drawPrompt(this.q('.image'), ['Press Render', `${this.stage} renders the scene here`]);
    }

    // The scene's references (tests/reference/), the stage's kind first:
    // global illumination for path tracers (07 on), direct light before.
    showReferences() {
        const refs = (page.scene && page.scene.references) || [];
        const box = this.q('.reference');
        box.hidden = refs.length === 0 || !this.result;
        const select = this.q('.reference-file');
        const kind = this.stage >= '07' ? '_gi.pfm' : '_direct.pfm';
        const ordered = refs.filter((r) => r.endsWith(kind)).concat(refs.filter((r) => !r.endsWith(kind)));
        const same = select.options.length === ordered.length && ordered.every((r, i) => select.options[i].value === r);
        if (!same) {
            select.textContent = '';
            for (const r of ordered) select.add(new Option(r.replace(/^reference\//, ''), r));
        }
        if (!box.hidden) this.drawReference();
    }

    async drawReference() {
        const path = this.q('.reference-file').value;
        const info = this.q('.errstats');
        if (!path || !this.result) return;
        const ref = parsePfm(await fetchFile(path, false));
        if (ref.width !== this.result.width || ref.height !== this.result.height) {
            info.textContent = `the reference is ${ref.width}x${ref.height}: render at that size to compare`;
            this.q('.errmap').hidden = true;
            return;
        }
        this.q('.errmap').hidden = false;
        const relmse = drawErrorMap(this.q('.errmap'), this.result.rgb, ref);
        info.textContent = `relMSE ${relmse.toExponential(3)} (blue: darker than the reference, red: brighter; saturates at 50%)`;
    }

    async encode(format) {
        const r = this.result;
        const worker = new Worker('worker.js');
        const answer = await ask(worker, {type: 'encode', stage: r.stage, rgb: r.rgb, width: r.width, height: r.height, format});
        worker.terminate();
        return answer.bytes;
    }

    async download(format) {
        const r = this.result;
        const name = `${r.stage}_${r.scene.path.replace(/^.*\//, '').replace(/\.[^.]*$/, '')}`;
        if (format === 'json') {
            download(name + '.json', JSON.stringify(r.stats, null, 2) + '\n', 'application/json');
        } else {
            download(`${name}.${format}`, await this.encode(format), format === 'png' ? 'image/png' : 'image/x-portable-floatmap');
        }
    }

    // Click on the image: the path trace of that pixel, by the stage's own
    // --pixel X,Y --trace-svg over the image just rendered.
    async inspect(event) {
        const r = this.result;
        if (!r) return;
        const canvas = this.q('.image');
        const box = canvas.getBoundingClientRect();
        const x = Math.min(r.width - 1, Math.floor(((event.clientX - box.left) / box.width) * r.width));
        const y = Math.min(r.height - 1, Math.floor(((event.clientY - box.top) / box.height) * r.height));
        return inspectPixel(this, x, y);
    }
}

async function inspectPixel(panel, x, y) {
    const r = panel.result;
    $('inspector').hidden = false;
    $('inspector-pixel').textContent = `${x},${y} in ${r.stage}`;
    const body = $('inspector-body');
    body.textContent = 'tracing...';
    const worker = new Worker('worker.js');
    const log = [];
    const request = {type: 'trace', stage: r.stage, args: r.args.concat(['--pixel', `${x},${y}`]), scene: r.scene.path, files: r.files, rgb: r.rgb, width: r.width, height: r.height};
    const answer = await ask(worker, request, (m) => m.type === 'log' && log.push(m.line));
    worker.terminate();
    body.textContent = '';
    if (answer.status !== 0 || !answer.svg) {
        const pre = document.createElement('pre');
        pre.className = 'errors';
        pre.textContent = log.join('\n') || answer.failure || 'no trace';
        body.appendChild(pre);
        return {status: answer.status, log};
    }
    const img = document.createElement('img');
    img.alt = `the paths of pixel ${x},${y}`;
    img.src = URL.createObjectURL(new Blob([answer.svg], {type: 'image/svg+xml'}));
    body.appendChild(img);
    if (log.length) {
        const note = document.createElement('p');
        note.className = 'note';
        note.textContent = log.join('\n');
        body.appendChild(note);
    }
    return {status: 0, log, svg: answer.svg};
}

// --- the page ------------------------------------------------------------

function workerCount() {
    const n = Number($('workers').value);
    return n >= 1 ? Math.floor(n) : 1;
}

async function renderAll() {
    const scene = currentScene();
    const files = await sceneFiles(scene);
    const panels = $('compare').checked ? page.panels : page.panels.slice(0, 1);
    const total = workerCount();
    $('render').disabled = true;
    $('stop').disabled = false;
    try {
        // Side by side, the panels share the workers.
        const each = Math.max(1, Math.floor(total / panels.length));
        return await Promise.all(panels.map((p) => p.render(scene, files, each)));
    } finally {
        $('render').disabled = false;
        $('stop').disabled = true;
    }
}

function showComparison() {
    page.panels[1].root.hidden = !$('compare').checked;
}

async function start() {
    page.library = await (await fetch('library.json')).json();
    const select = $('scene');
    for (const s of page.library.scenes) select.add(new Option(s.name, s.name));
    select.value = page.library.scenes.some((s) => s.name === 'cornell_diffuse_area') ? 'cornell_diffuse_area' : page.library.scenes[0].name;
    $('left-out').textContent = page.library.left_out.map((l) => `Not bundled: ${l.name} (${l.why}).`).join(' ');
    $('workers').value = Math.max(1, Math.min(16, navigator.hardwareConcurrency || 2));
    page.panels = [new Panel(0), new Panel(1)];
    showComparison();
    await chooseLibraryScene(select.value);
    page.panels.forEach((p) => p.redraw());
    select.onchange = () => chooseLibraryScene(select.value);
    // One scene among the files chosen (the first .scene, else the first
    // glTF file), the others its models.
    $('upload').onchange = () => {
        const chosen = Array.from($('upload').files);
        const scene = chosen.find((f) => f.name.endsWith('.scene')) || chosen[0];
        if (!scene) return;
        chosen.filter((f) => f !== scene).forEach(uploadModel);
        uploadScene(scene);
    };
    $('render').onclick = () => renderAll();
    $('stop').onclick = () => {
        for (const p of page.panels) p.stop();
    };
    $('compare').onchange = showComparison;
    $('exposure').oninput = () => {
        $('exposure-value').textContent = $('exposure').value + ' EV';
        page.panels.forEach((p) => p.redraw());
    };
    $('tonemap').onchange = () => page.panels.forEach((p) => p.redraw());
    $('inspector-close').onclick = () => ($('inspector').hidden = true);
}

// What tests/web/test_browser.py drives: the controls set as a user would,
// then the Render button's action; results as plain values.
window.stagelight = {
    ready: start(),
    async render(settings) {
        await this.ready;
        if (settings.scene) {
            $('scene').value = settings.scene;
            await chooseLibraryScene(settings.scene);
        }
        if (typeof settings.sceneText === 'string') $('scene-text').value = settings.sceneText;
        for (const key of ['width', 'height', 'spp', 'seed', 'workers']) {
            if (key in settings) $(key).value = settings[key];
        }
        $('compare').checked = !!settings.stage2;
        showComparison();
        const stages = [settings.stage, settings.stage2].filter(Boolean);
        await Promise.all(stages.map((s, i) => {
            page.panels[i].q('.stage').value = s;
            return page.panels[i].loadOptions();
        }));
        const results = await renderAll();
        return results.map((r, i) => ({status: r.status, log: r.log, stats: r.stats, errorsShown: page.panels[i].q('.errors').hidden ? '' : page.panels[i].q('.errors').textContent}));
    },
    // The PFM the panel's download button gives, base64.
    async pfm(panel) {
        const bytes = await page.panels[panel].encode('pfm');
        let s = '';
        for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
        return btoa(s);
    },
    async inspect(panel, x, y) {
        const r = await inspectPixel(page.panels[panel], x, y);
        const img = document.querySelector('#inspector-body img');
        return {status: r.status, visible: !$('inspector').hidden && !!img, svg: r.svg || ''};
    },
};
