#!/usr/bin/env python3
"""chromium.py - headless Chromium driven over its DevTools protocol
(--remote-debugging-pipe: file descriptors 3 and 4, one JSON message per
NUL-terminated line).  The make-web page's test (tests/web/test_browser.py)
drives a page with it; the C tests' screenshots (tests/lib/browser.c) run
it as a command:

  chromium.py PAGE WIDTH HEIGHT SHOT.png HOME

opens the file PAGE in a WIDTHxHEIGHT viewport, waits until the page has
loaded, every image on it is decoded and two frames have been drawn, and
writes the viewport to SHOT.png.  Chromium's profile, HOME and TMPDIR are
in HOME.  Exit 0, or 1 with the reason on stderr.

Why not Chromium's own --screenshot: it takes the picture when a time
budget (--virtual-time-budget) runs out, not when the page is painted.  On
a loaded machine (two busy processes beside it) it took pictures of
half-painted pages in 10 of 57 runs of test_report_browser (the report
page without its slider).  --run-all-compositor-stages-before-draw made
that 0 of 25, as did this script; here the conditions are stated rather
than left to a flag's timing.
"""
import base64
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

# Resolves once the document has loaded, its images are decoded and two
# animation frames have passed (the second after the first was painted).
SETTLED = """new Promise(done => {
  const frames = () => requestAnimationFrame(() => requestAnimationFrame(() => done(true)));
  const images = () => Promise.all(Array.from(document.images || [],
                                              i => i.decode().catch(() => null))).then(frames);
  if (document.readyState === 'complete') images();
  else addEventListener('load', images);
})"""


class Chromium:
    """Headless Chromium driven over --remote-debugging-pipe."""

    def __init__(self, home):
        # Chromium puts Unix sockets in its TMPDIR, whose paths must stay
        # under 108 bytes (sun_path): a HOME nested in a test's temporary
        # directory passes that when TMPDIR is long (a folder under /tmp of
        # 26 characters did; macOS's is longer).  A home longer than 32
        # characters is replaced by a short one under /tmp, removed by
        # close().
        self.short_home = None
        if len(home) > 32:
            self.short_home = tempfile.mkdtemp(prefix='slcr.', dir='/tmp')
            home = self.short_home
        self.to_browser_r, self.to_browser_w = os.pipe()
        self.from_browser_r, self.from_browser_w = os.pipe()
        env = dict(os.environ, HOME=home, TMPDIR=home)
        chromium = os.environ.get('CHROMIUM') or shutil.which('chromium') or '/usr/bin/chromium'
        args = [chromium, '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
                '--no-first-run', '--disable-background-networking', '--disable-component-update',
                '--disable-sync', '--hide-scrollbars',
                '--user-data-dir=' + os.path.join(home, 'profile'), '--remote-debugging-pipe',
                'about:blank']

        def pipes():
            os.dup2(self.to_browser_r, 3)
            os.dup2(self.from_browser_w, 4)

        # A session of its own: close() stops its helper processes too.
        try:
            self.proc = subprocess.Popen(args, env=env, preexec_fn=pipes, pass_fds=(3, 4),
                                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                         start_new_session=True)
        except OSError:
            if self.short_home:
                shutil.rmtree(self.short_home, ignore_errors=True)
            raise
        os.close(self.to_browser_r)
        os.close(self.from_browser_w)
        self.buffer = b''
        self.next_id = 1
        self.session = None

    def send(self, method, params=None, timeout=300):
        msg = {'id': self.next_id, 'method': method, 'params': params or {}}
        if self.session:
            msg['sessionId'] = self.session
        self.next_id += 1
        os.write(self.to_browser_w, json.dumps(msg).encode() + b'\0')
        deadline = time.time() + timeout
        while True:
            while b'\0' not in self.buffer:
                if time.time() > deadline:
                    raise TimeoutError(method)
                chunk = os.read(self.from_browser_r, 1 << 20)
                if not chunk:
                    raise EOFError('Chromium closed its pipe')
                self.buffer += chunk
            line, self.buffer = self.buffer.split(b'\0', 1)
            answer = json.loads(line)
            if answer.get('id') == msg['id']:
                if 'error' in answer:
                    raise RuntimeError('%s: %s' % (method, answer['error']))
                return answer['result']

    def open(self, url):
        target = self.send('Target.createTarget', {'url': url})['targetId']
        self.session = self.send('Target.attachToTarget',
                                 {'targetId': target, 'flatten': True})['sessionId']

    def evaluate(self, expression):
        """The value of a JavaScript expression (awaited if a promise)."""
        r = self.send('Runtime.evaluate', {'expression': expression, 'awaitPromise': True,
                                           'returnByValue': True})
        if 'exceptionDetails' in r:
            raise RuntimeError(json.dumps(r['exceptionDetails'])[:2000])
        return r['result'].get('value')

    def viewport(self, width, height):
        self.send('Emulation.setDeviceMetricsOverride', {'width': width, 'height': height,
                                                          'deviceScaleFactor': 1, 'mobile': False})

    def screenshot(self, path, width, height):
        self.viewport(width, height)
        self.capture(path)

    def capture(self, path):
        """The viewport as it is, into the PNG file path."""
        shot = self.send('Page.captureScreenshot', {'format': 'png'})
        with open(path, 'wb') as f:
            f.write(base64.b64decode(shot['data']))

    def close(self):
        """Ask Chromium to quit, then stop whatever of its session is left:
        a helper outliving it could still write into its profile (in the
        test's temporary directory) after the test removed it."""
        try:
            self.send('Browser.close', timeout=10)
        except (RuntimeError, TimeoutError, EOFError, OSError):
            pass
        try:
            self.proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        try:
            os.killpg(self.proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        os.close(self.to_browser_w)
        os.close(self.from_browser_r)
        if self.short_home:
            shutil.rmtree(self.short_home, ignore_errors=True)


def screenshot(page, width, height, shot, home):
    browser = Chromium(home)
    try:
        browser.open('about:blank')
        browser.viewport(width, height)
        url = 'file://' + urllib.request.pathname2url(os.path.abspath(page))
        browser.send('Page.navigate', {'url': url})
        # Page.navigate may answer before the new document is committed;
        # until then an evaluation still runs in about:blank.
        deadline = time.time() + 120
        while browser.evaluate('location.protocol') != 'file:':
            if time.time() > deadline:
                raise TimeoutError('the page did not open: ' + url)
            time.sleep(0.05)
        browser.evaluate(SETTLED)
        browser.capture(shot)
    finally:
        browser.close()


def main():
    if len(sys.argv) != 6:
        sys.exit('usage: chromium.py PAGE WIDTH HEIGHT SHOT.png HOME')
    page, width, height, shot, home = sys.argv[1:]
    # A caller's timeout (SIGTERM) still closes Chromium: see close().
    signal.signal(signal.SIGTERM, lambda *_: sys.exit('chromium.py: stopped (SIGTERM)'))
    try:
        screenshot(page, int(width), int(height), shot, home)
    except (RuntimeError, TimeoutError, EOFError, OSError, ValueError) as e:
        sys.exit('chromium.py: %s' % e)


if __name__ == '__main__':
    main()
