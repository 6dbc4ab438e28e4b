#!/usr/bin/env python3
"""test_browser.py - the page of make web, in a real browser.

Serves build/web/ with python3 -m http.server on 127.0.0.1 (started here,
stopped by its pid), opens index.html in headless Chromium and drives the
page through window.stagelight (common/web/app.js: it sets the page's
controls and presses Render), speaking Chromium's DevTools protocol
(tests/lib/chromium.py).  Checks, against the native build of the same stage:

  - cornell_diffuse_area in stages 01 and 07, side by side, at 64x64 with
    16 spp, seed 7, on 3 workers: the PFM the page's download button gives
    equals the native render's to within libm's rounding (tolerance below);
    and the native render of another seed is NOT within it (the comparison
    can fail);
  - a malformed scene: the page shows the stage's located error, the same
    FILE:LINE:COL: error: line as the native build prints;
  - the pixel inspector opens on a click's pixel and shows the path picture,
    the same SVG as the native --pixel X,Y --trace-svg;
  - every scene of the library renders in every stage (EVERY_SIZE pixels
    wide, 1 spp: what is checked is that it loads and renders, with finite
    pixels), and every scene of scenes/ is either in the library or left out
    with its reason (library.json's left_out: the Buddha).

Prints one line per check and "N passed, N failed, N skipped" last; skips
(with the reason) when there is no Chromium or no build/web/.

test_browser.py --screenshot FILE.png: instead, the README's picture of the
page: stages 03 and 07 side by side on cornell_diffuse_area, 64 spp.
"""
import base64
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'lib'))
from chromium import Chromium  # noqa: E402  (tests/lib/chromium.py)

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
WEB = os.path.join(ROOT, 'build', 'web')
SIZE = 64
SPP = 16
SEED = 7
WORKERS = 3  # 16 tiles of 16x16: shares of 6, 5 and 5 tiles
SCENE = 'cornell_diffuse_area'
STAGES = ['01_raycast', '07_pathtrace']
# Largest difference allowed between a browser and a native pixel: relative
# to the pixel's value, floored at 1e-3 for dark ones.  Both builds run the
# same code on IEEE doubles; only libm differs (glibc natively, musl in the
# browser build), whose results may differ in the last bit; measured: see
# docs/web.md.
TOLERANCE = 1e-4
# Width of the every-scene renders: small, since stages 01-04 test every
# triangle of the bunnies for every ray.
EVERY_SIZE = 12

passed = failed = skipped = 0


def result(ok, name, detail=''):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
    print(('ok   ' if ok else 'FAIL ') + name + (': ' + detail if detail else ''))
    sys.stdout.flush()


def finish():
    print('%d passed, %d failed, %d skipped' % (passed, failed, skipped))
    sys.exit(1 if failed else 0)


def skip(reason):
    global skipped
    skipped += 1
    print('skip web: ' + reason)
    finish()


def read_pfm(data):
    """(width, height, floats top row first) of a colour PFM file."""
    header = []
    pos = 0
    while len(header) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        header.append(data[start:pos].decode())
    pos += 1
    if header[0] != 'PF':
        raise ValueError('not a colour PFM')
    width, height, scale = int(header[1]), int(header[2]), float(header[3])
    fmt = ('<' if scale < 0 else '>') + '%df' % (width * height * 3)
    rows = struct.unpack_from(fmt, data, pos)
    row = width * 3
    floats = []
    for y in range(height - 1, -1, -1):
        floats.extend(rows[y * row:(y + 1) * row])
    return width, height, floats


def largest_difference(a, b):
    """(largest |a - b| / max(|b|, 1e-3), its index) over two PFMs' floats."""
    worst, where = 0.0, -1
    for i, (x, y) in enumerate(zip(a, b)):
        d = abs(x - y) / max(abs(y), 1e-3)
        if d > worst:
            worst, where = d, i
    return worst, where


def native(stage, args, cwd):
    """Run a stage's native binary in cwd, where scenes/ is the scenes the
    page has (the same paths in messages and pictures); (status, stderr)."""
    binary = os.path.join(ROOT, 'build', stage, 'render')
    p = subprocess.run([binary, '-q'] + args, cwd=cwd, capture_output=True, text=True)
    return p.returncode, p.stderr


def serve(directory):
    """python3 -m http.server on a free port of 127.0.0.1: (process, port)."""
    proc = subprocess.Popen([sys.executable, '-u', '-m', 'http.server', '--bind', '127.0.0.1',
                             '--directory', directory, '0'],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    line = proc.stdout.readline()
    m = re.search(r'port (\d+)', line)
    if not m:
        proc.terminate()
        proc.wait()
        raise RuntimeError('http.server said: ' + line)
    return proc, int(m.group(1))


def check_prompt(browser, tmp):
    """Before any render the first panel says what to do, on a canvas that
    is not black (the page opened on a black square until Render)."""
    lit = browser.evaluate(
        "(() => { const c = document.querySelector('.panel canvas.image');"
        " const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
        " let n = 0; for (let i = 0; i < d.length; i += 4) n += d[i] > 128; return n; })()")
    result(lit > 50, 'prompt-before-render', '%d light pixels (the prompt\'s text)' % lit)


def check_images(browser, tmp):
    options = ['-W', str(SIZE), '--spp', str(SPP)]
    scene_path = 'scenes/%s.scene' % SCENE
    answers = browser.evaluate('stagelight.render(%s)' % json.dumps({
        'scene': SCENE, 'stage': STAGES[0], 'stage2': STAGES[1], 'width': SIZE, 'height': '',
        'spp': SPP, 'seed': SEED, 'workers': 2 * WORKERS}))
    for panel, stage in enumerate(STAGES):
        a = answers[panel]
        if a['status'] != 0:
            result(False, stage + ' renders in the page', '\n'.join(a['log']))
            continue
        page = read_pfm(base64.b64decode(browser.evaluate('stagelight.pfm(%d)' % panel)))
        out = os.path.join(tmp, stage + '.pfm')
        status, err = native(stage, options + ['--seed', str(SEED), '-o', out, scene_path], tmp)
        with open(out, 'rb') as f:
            want = read_pfm(f.read())
        os.remove(out)
        same_size = page[:2] == want[:2] == (SIZE, SIZE)
        worst, where = largest_difference(page[2], want[2]) if same_size else (float('inf'), -1)
        at = ('' if where < 0 else ' at pixel %d,%d channel %d'
              % ((where // 3) % SIZE, where // 3 // SIZE, where % 3))
        result(status == 0 and same_size and worst <= TOLERANCE,
               '%s: the page\'s image is the native one' % stage,
               'largest relative difference %.3g%s (%d workers, %s spp)'
               % (worst, at, a['stats']['web_workers'], a['stats']['spp']))
        status, _ = native(stage, options + ['--seed', str(SEED + 1), '-o', out, scene_path], tmp)
        with open(out, 'rb') as f:
            other = read_pfm(f.read())
        os.remove(out)
        worst_other, _ = largest_difference(page[2], other[2])
        if stage != STAGES[0]:  # stage 01 draws no random numbers: every seed is one image
            result(status == 0 and worst_other > TOLERANCE,
                   '%s: the comparison fails for an image that differs (seed %d against %d)'
                   % (stage, SEED, SEED + 1), 'largest relative difference %.3g' % worst_other)


def check_error(browser, tmp):
    with open(os.path.join(ROOT, 'scenes', SCENE + '.scene')) as f:
        text = f.read()
    broken = text.replace('radius 0.40', 'radius 0.40 0.1', 1)
    where = os.path.join(tmp, 'broken')
    os.makedirs(os.path.join(where, 'scenes'))
    with open(os.path.join(where, 'scenes', SCENE + '.scene'), 'w') as f:
        f.write(broken)
    status, err = native(STAGES[1], ['-o', 'x.pfm', 'scenes/%s.scene' % SCENE], where)
    shutil.rmtree(where)
    want = [l for l in err.splitlines() if ': error: ' in l]
    a = browser.evaluate('stagelight.render(%s)' % json.dumps({
        'scene': SCENE, 'sceneText': broken, 'stage': STAGES[1], 'width': SIZE, 'workers': 2}))[0]
    shown = a['errorsShown']
    located = re.match(r'scenes/%s\.scene:\d+:\d+: error: ' % SCENE, shown)
    result(status == 1 and a['status'] == 1 and bool(located) and want == shown.splitlines(),
           'a malformed scene shows its located error',
           'page: %r, native: %r' % (shown, want))


def check_inspector(browser, tmp):
    x, y = 20, 45
    # The last render was the malformed scene: render the library's again.
    a = browser.evaluate('stagelight.render(%s)' % json.dumps({
        'scene': SCENE, 'stage': STAGES[1], 'width': SIZE, 'spp': SPP,
        'seed': SEED, 'workers': 2}))[0]
    shown = browser.evaluate('stagelight.inspect(0, %d, %d)' % (x, y))
    svg = os.path.join(tmp, 'trace.svg')
    scene_path = 'scenes/%s.scene' % SCENE
    status, _ = native(STAGES[1], ['-W', str(SIZE), '--spp', str(SPP), '--seed', str(SEED),
                                   '--pixel', '%d,%d' % (x, y), '--trace-svg', svg, scene_path], tmp)
    with open(svg) as f:
        want = f.read()
    os.remove(svg)
    result(a['status'] == 0 and shown['status'] == 0 and shown['visible'],
           'the pixel inspector opens with the path picture', json.dumps(shown)[:300])
    result(shown.get('svg') == want,
           'the inspector\'s picture is the native --trace-svg', '%d bytes against %d'
           % (len(shown.get('svg', '')), len(want)))


def check_every_scene(browser, tmp):
    with open(os.path.join(WEB, 'library.json')) as f:
        library = json.load(f)
    bundled = [s['name'] for s in library['scenes']]
    left_out = {s['name']: s['why'] for s in library['left_out']}
    ours = sorted(os.path.splitext(n)[0] for n in os.listdir(os.path.join(ROOT, 'scenes'))
                  if n.endswith('.scene') or n.endswith('.gltf'))
    unaccounted = [n for n in ours if n not in bundled and not left_out.get(n)]
    result(not unaccounted and bool(bundled),
           'every scene of scenes/ is in the page\'s library or left out with its reason',
           '%d bundled, left out: %s; neither: %s' % (len(bundled), ', '.join(sorted(left_out)) or 'none',
                                                    ', '.join(unaccounted) or 'none'))
    stages = sorted(d for d in os.listdir(os.path.join(ROOT, 'stages')) if re.match(r'\d\d_', d))
    result(library['stages'] == stages, 'the page offers every stage of stages/',
           'page: %s; stages/: %s' % (' '.join(library['stages']), ' '.join(stages)))
    failures = []
    for stage in library['stages']:
        for name in bundled:
            a = browser.evaluate('stagelight.render(%s)' % json.dumps({
                'scene': name, 'stage': stage, 'width': EVERY_SIZE, 'height': '', 'spp': 1,
                'seed': 1, 'workers': 2}))[0]
            if a['status'] != 0:
                failures.append('%s %s: status %s: %s' % (stage, name, a['status'],
                                                         (a['errorsShown'] or ' '.join(a['log']))[:200]))
                continue
            w, h, pixels = read_pfm(base64.b64decode(browser.evaluate('stagelight.pfm(0)')))
            bad = sum(1 for v in pixels if not math.isfinite(v))
            if w != EVERY_SIZE or h < 1 or len(pixels) != 3 * w * h or bad:
                failures.append('%s %s: %dx%d, %d pixel values not finite' % (stage, name, w, h, bad))
    result(not failures, 'every scene of the library renders in every stage (%d scenes x %d stages)'
           % (len(bundled), len(library['stages'])), '; '.join(failures[:5]))


def main():
    chromium = os.environ.get('CHROMIUM') or shutil.which('chromium')
    if not chromium:
        skip('no Chromium: apt-get install chromium (or set CHROMIUM) to test the page')
    if not os.path.exists(os.path.join(WEB, 'index.html')):
        skip('no build/web/: make web (needs emscripten: apt-get install emscripten)')
    tmp = tempfile.mkdtemp(prefix='sl-web.')
    os.symlink(os.path.join(ROOT, 'scenes'), os.path.join(tmp, 'scenes'))
    server = browser = None
    try:
        server, port = serve(WEB)
        browser = Chromium(tmp)
        browser.open('http://127.0.0.1:%d/index.html' % port)
        for _ in range(600):
            try:
                if browser.evaluate('!!window.stagelight && stagelight.ready.then(() => true)'):
                    break
            except RuntimeError:
                pass
            time.sleep(0.1)
        if len(sys.argv) == 3 and sys.argv[1] == '--screenshot':
            browser.evaluate('stagelight.render(%s)' % json.dumps({
                'scene': SCENE, 'stage': '03_soft_shadows', 'stage2': '07_pathtrace', 'spp': 64,
                'workers': os.cpu_count()}))
            browser.evaluate('stagelight.inspect(1, 180, 200)')
            browser.screenshot(sys.argv[2], 1200, 1800)
            return
        for check in (check_prompt, check_images, check_error, check_inspector, check_every_scene):
            try:
                check(browser, tmp)
            except (RuntimeError, TimeoutError, EOFError, OSError, ValueError) as e:
                result(False, check.__name__, str(e)[:2000])
    finally:
        if browser:
            browser.close()
        if server:
            server.terminate()
            server.wait()
        for _ in range(50):
            shutil.rmtree(tmp, ignore_errors=True)
            if not os.path.exists(tmp):
                break
            time.sleep(0.1)
    finish()


if __name__ == '__main__':
    main()
