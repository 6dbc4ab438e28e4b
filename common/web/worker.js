// worker.js - one Web Worker of the page (app.js): runs a stage's own
// main() (compiled by make web, stages/NN_name.js) on a command line, in a
// fresh module instance per request, with the scene and its models in the
// module's in-memory file system at the paths they have in the repository
// (scenes/NAME.scene, scenes/models/...), so messages name files as the
// native build does.
//
// Requests (postMessage), each answered by {type: 'done', id, ...}:
//   {type: 'render', id, stage, args, scene, files, part, parts}
//       render the tiles t % parts == part (web_main.c); every finished pass
//       is posted as {type: 'pass', id, rgb, width, height, passes}
//   {type: 'trace', id, stage, args, scene, files, rgb, width, height}
//       run with args (--pixel X,Y among them) and --trace-svg over the page's image; done.svg
//   {type: 'encode', id, stage, rgb, width, height, format}
//       the image as the native build writes it (png, pfm); done.bytes
//   {type: 'help', id, stage}  the stage's --help text; done.text
// Everything the stage prints comes as {type: 'log', id, line, stream}.
'use strict';

const factories = {};

function factory(stage) {
    if (!/^[0-9][0-9]_[a-z0-9_]+$/.test(stage)) {
        throw new Error('no stage ' + stage);
    }
    if (!factories[stage]) {
        self.createStage = undefined;
        importScripts('stages/' + stage + '.js');
        factories[stage] = self.createStage;
    }
    return factories[stage];
}

// A fresh instance of the stage's module, its output posted line by line.
async function instance(request, onPass) {
    const post = (stream) => (line) => self.postMessage({type: 'log', id: request.id, stream, line});
    return factory(request.stage)({print: post('stdout'), printErr: post('stderr'), onPass});
}

function writeFiles(mod, files) {
    for (const path of Object.keys(files || {})) {
        const parts = path.split('/');
        let dir = '';
        for (const p of parts.slice(0, -1)) {
            dir += '/' + p;
            try {
                mod.FS.mkdir(dir);
            } catch (e) {
                /* exists already */
            }
        }
        mod.FS.writeFile('/' + path, typeof files[path] === 'string' ? files[path] : new Uint8Array(files[path]));
    }
    mod.FS.mkdir('/out');
}

// main() on args; the exit status (emscripten reports exit() as a throw).
function runMain(mod, args) {
    try {
        return mod.callMain(args);
    } catch (e) {
        if (e && e.name === 'ExitStatus') {
            return e.status;
        }
        throw e;
    }
}

function readText(mod, path) {
    try {
        return mod.FS.readFile(path, {encoding: 'utf8'});
    } catch (e) {
        return null;
    }
}

// Copy the page's image into the module (floats the module allocated).
function putImage(mod, where, rgb) {
    mod.HEAPF32.set(rgb, where >> 2);
}

const handlers = {
    async render(req) {
        const mod = await instance(req, (rgb, width, height, passes) =>
            self.postMessage({type: 'pass', id: req.id, rgb, width, height, passes}, [rgb.buffer]));
        writeFiles(mod, req.files);
        mod._web_set_share(req.part, req.parts);
        const status = runMain(mod, req.args.concat(['-q', '-t', '1', '--stats', '/out/stats.json', '-o', '/out/image.pfm', req.scene]));
        return {status, stats: readText(mod, '/out/stats.json')};
    },
    async trace(req) {
        const mod = await instance(req, () => {});
        writeFiles(mod, req.files);
        const where = mod._web_use_rendered(req.width, req.height);
        if (!where) {
            return {status: 4, svg: null};
        }
        putImage(mod, where, req.rgb);
        const status = runMain(mod, req.args.concat(['-q', '-t', '1', '--trace-svg', '/out/trace.svg', req.scene]));
        return {status, svg: readText(mod, '/out/trace.svg')};
    },
    async encode(req) {
        const mod = await instance(req, () => {});
        writeFiles(mod, {});
        const bytes = req.rgb.length * 4;
        const where = mod._malloc(bytes);
        putImage(mod, where, req.rgb);
        const path = '/out/image.' + (req.format === 'png' ? 'png' : 'pfm');
        const name = mod._malloc(64);
        mod.stringToUTF8(path, name, 64);
        const status = mod._web_write_image(where, req.width, req.height, name);
        mod._free(where);
        mod._free(name);
        return {status, bytes: status === 0 ? mod.FS.readFile(path) : null};
    },
    async help(req) {
        const lines = [];
        const mod = await factory(req.stage)({print: (l) => lines.push(l), printErr: (l) => lines.push(l)});
        runMain(mod, ['--help']);
        return {status: 0, text: lines.join('\n')};
    },
};

self.onmessage = async (event) => {
    const req = event.data;
    try {
        const answer = await handlers[req.type](req);
        self.postMessage(Object.assign({type: 'done', id: req.id}, answer));
    } catch (e) {
        self.postMessage({type: 'done', id: req.id, status: -1, failure: String(e && e.stack ? e.stack : e)});
    }
};
