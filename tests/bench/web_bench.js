// web_bench.js WEB STAGE SCENE WORKERS ARGS... - the browser build's speed
// (web_bench.sh prints it beside the native build's): renders SCENE with
// build/web/stages/STAGE.js under node (V8, the engine of Chromium) as the
// page does, in WORKERS worker threads each on a share of the tiles
// (web_main.c), and prints one JSON line: the rays of all shares, the wall
// time from the first share's start to the last one's end, rays per second.
'use strict';
const fs = require('fs');
const path = require('path');
const {Worker, isMainThread, parentPort, workerData} = require('worker_threads');

// One share of the render in this thread: its --stats object.
async function renderShare({web, stage, scene, args, part, parts}) {
    const create = require(path.join(web, 'stages', stage + '.js'));
    const mod = await create({print: () => {}, printErr: (l) => process.stderr.write(l + '\n'), onPass: () => {}});
    // The scene and the models it needs, as the page has them (library.json).
    const library = JSON.parse(fs.readFileSync(path.join(web, 'library.json'), 'utf8'));
    const entry = library.scenes.find((s) => s.file === 'scenes/' + path.basename(scene));
    mod.FS.mkdir('/scenes');
    mod.FS.mkdir('/scenes/models');
    for (const file of [entry.file].concat(entry.needs)) {
        mod.FS.writeFile('/' + file, fs.readFileSync(path.join(web, file)));
    }
    mod._web_set_share(part, parts);
    const status = mod.callMain(args.concat(['-q', '--stats', '/stats.json', '-o', '/image.pfm',
        'scenes/' + path.basename(scene)]));
    if (status !== 0) {
        throw new Error(stage + ' exited ' + status);
    }
    return JSON.parse(mod.FS.readFile('/stats.json', {encoding: 'utf8'}));
}

async function main() {
    const [web, stage, scene, workers, ...args] = process.argv.slice(2);
    const parts = Number(workers);
    const start = process.hrtime.bigint();
    const shares = await Promise.all(Array.from({length: parts}, (_, part) => new Promise((resolve, reject) => {
        const w = new Worker(__filename, {workerData: {web: path.resolve(web), stage, scene, args, part, parts}});
        w.once('message', resolve);
        w.once('error', reject);
    })));
    const seconds = Number(process.hrtime.bigint() - start) / 1e9;
    const rays = shares.reduce((sum, s) => sum + s.rays_camera + s.rays_shadow + s.rays_secondary, 0);
    const render = Math.max(...shares.map((s) => s.seconds_render));
    console.log(JSON.stringify({workers: parts, rays, seconds_render: render, seconds_wall: seconds,
        rays_per_second: rays / render}));
}

if (isMainThread) {
    main().catch((e) => {
        console.error('web_bench: ' + e.message);
        process.exit(1);
    });
} else {
    renderShare(workerData).then((stats) => parentPort.postMessage(stats));
}
