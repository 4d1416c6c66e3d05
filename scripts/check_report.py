#!/usr/bin/python3
"""Open a granvv report in a real (headless) Chromium and check that it renders.

Usage: /usr/bin/python3 scripts/check_report.py DIR_OR_report.html [--screenshot PNG] [--timeout S]

The report folder is served over http://127.0.0.1:<free port> (so relative figure paths load as
they do in a browser) and opened through chromedriver with plain W3C WebDriver requests (standard
library only, no selenium). Checks:
  (a) the page has a non-empty <title> and at least one <h1>/<h2>;
  (b) every <img> has complete == true and naturalWidth > 0;
  (c) no browser console message of level SEVERE (JavaScript errors, console.error, failed loads),
      and no HTTP error (404, ...) answered by the local server.
Prints a one-line verdict, then details. Exit codes: 0 pass, 1 a check failed, 2 usage error or the
browser could not be started. chromedriver, Chromium and the temporary profile are always removed,
and the whole check is bounded by --timeout (default 60 s).

chromedriver (Debian 156) notes: the browser log is read with POST /session/{id}/se/log
{"type": "browser"}; the legacy alias POST /session/{id}/log works too, but GET
/session/{id}/log/browser does not exist ("unknown command") and GET /session/{id}/log/types is
refused in W3C mode. Reading the log drains it: every read returns only the new entries.
"""

import argparse
import base64
import functools
import http.server
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.parse
import urllib.request

CHROMEDRIVER = "/usr/bin/chromedriver"
CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
EXIT_PASS, EXIT_FAIL, EXIT_ERROR = 0, 1, 2

# Run in the page: the facts the checks need, as one JSON-able object.
PAGE_FACTS_JS = """
const imgs = Array.from(document.images);
for (const i of imgs) if (i.loading === 'lazy') i.loading = 'eager';
return {
  readyState: document.readyState,
  title: document.title,
  headings: document.querySelectorAll('h1, h2').length,
  images: imgs.map(i => ({src: i.getAttribute('src'), url: i.currentSrc || i.src,
                          complete: i.complete, naturalWidth: i.naturalWidth}))
};
"""


class UsageError(Exception):
    pass


class BrowserError(Exception):
    """chromedriver or Chromium could not be started or stopped answering."""


class OverallTimeout(Exception):
    pass


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


# urllib without any proxy from the environment: everything here is on 127.0.0.1.
_OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))


class WebDriver:
    """Just enough of the W3C WebDriver protocol, over urllib."""

    def __init__(self, base_url, deadline):
        self.base_url = base_url
        self.deadline = deadline
        self.session = None

    def _timeout(self, cap=None):
        left = max(1.0, self.deadline - time.monotonic())
        return min(left, cap) if cap else left

    def request(self, method, path, body=None, timeout=None):
        """Returns (HTTP status, the "value" of the answer)."""
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base_url + path, data=data, method=method,
                                     headers={"Content-Type": "application/json; charset=utf-8"})
        try:
            with _OPENER.open(req, timeout=timeout or self._timeout()) as answer:
                status, raw = answer.status, answer.read()
        except urllib.error.HTTPError as e:
            status, raw = e.code, e.read()
        try:
            value = json.loads(raw or b"null")
            value = value.get("value") if isinstance(value, dict) else value
        except ValueError:
            value = raw.decode(errors="replace")
        return status, value

    def call(self, method, path, body=None, timeout=None):
        """Like request, but a WebDriver error raises BrowserError."""
        status, value = self.request(method, path, body, timeout)
        if status != 200:
            if isinstance(value, dict):
                message = f"{value.get('error')}: {str(value.get('message', '')).splitlines()[0]}"
            else:
                message = str(value)[:300]
            raise BrowserError(f"{method} {path} -> HTTP {status}: {message}")
        return value

    def session_call(self, method, path, body=None, timeout=None):
        return self.call(method, f"/session/{self.session}{path}", body, timeout)

    def browser_log(self):
        """New browser console entries (reading drains chromedriver's buffer)."""
        for method, path in (("POST", "/se/log"), ("POST", "/log")):
            status, value = self.request(method, f"/session/{self.session}{path}",
                                         {"type": "browser"})
            if status == 200 and isinstance(value, list):
                return value
        status, value = self.request("GET", f"/session/{self.session}/log/browser")
        if status == 200 and isinstance(value, list):
            return value
        raise BrowserError("chromedriver offers no browser log endpoint (tried POST se/log, "
                           "POST log, GET log/browser)")


def make_handler(root, seen, lock):
    """A quiet static-file handler for root that records (status, path) of every request."""

    class Handler(http.server.SimpleHTTPRequestHandler):
        def log_request(self, code="-", size="-"):
            try:
                code = int(getattr(code, "value", code))
            except (TypeError, ValueError):
                code = 0
            with lock:
                seen.append((code, urllib.parse.unquote(self.path)))

        def log_message(self, format, *args):  # no access log on stderr
            pass

        def do_GET(self):
            # Chromium asks for /favicon.ico on its own even when the page names no icon; a 404
            # there would be logged as a SEVERE network error that is not the report's fault.
            if (urllib.parse.urlsplit(self.path).path == "/favicon.ico"
                    and not os.path.exists(os.path.join(root, "favicon.ico"))):
                self.send_response(204)
                self.end_headers()
                return
            super().do_GET()

        def end_headers(self):
            self.send_header("Cache-Control", "no-store")
            super().end_headers()

    return functools.partial(Handler, directory=root)


def start_chromedriver(tmp, deadline):
    """Starts chromedriver on a free port; returns (process, WebDriver). Retries a taken port."""
    if not os.access(CHROMEDRIVER, os.X_OK):
        raise BrowserError(f"{CHROMEDRIVER} not found (Debian package chromium-driver; "
                           "scripts/setup.sh --browser installs it)")
    if not os.access(CHROMIUM, os.X_OK):
        raise BrowserError(f"{CHROMIUM} not found (Debian package chromium; "
                           "scripts/setup.sh --browser installs it)")
    log_path = os.path.join(tmp, "chromedriver.log")
    for _ in range(3):
        port = free_port()
        # TMPDIR: Chromium's own scratch folders (org.chromium.Chromium.*) land in tmp too and go
        # with it, even when Chromium is killed.
        env = dict(os.environ, TMPDIR=tmp)
        with open(log_path, "ab") as log:
            proc = subprocess.Popen([CHROMEDRIVER, f"--port={port}"], stdin=subprocess.DEVNULL,
                                    stdout=log, stderr=subprocess.STDOUT, env=env,
                                    start_new_session=True)
        driver = WebDriver(f"http://127.0.0.1:{port}", deadline)
        while proc.poll() is None and time.monotonic() < deadline:
            try:
                status, value = driver.request("GET", "/status", timeout=2)
                if status == 200 and isinstance(value, dict) and value.get("ready"):
                    return proc, driver
            except (OSError, urllib.error.URLError):
                pass
            time.sleep(0.1)
        stop_process_group(proc)
        if time.monotonic() >= deadline:
            break
    raise BrowserError("chromedriver did not become ready; its log ends with:\n" +
                       tail(log_path))


def stop_process_group(proc):
    """Ends chromedriver and the Chromium it started (its own process group), politely first."""
    if proc is None or proc.poll() is not None and not _group_alive(proc.pid):
        return
    for sig, wait in ((signal.SIGTERM, 5), (signal.SIGKILL, 5)):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            break
        end = time.monotonic() + wait
        while time.monotonic() < end and _group_alive(proc.pid):
            proc.poll()
            time.sleep(0.05)
        if not _group_alive(proc.pid):
            break
    try:
        proc.wait(timeout=1)
    except subprocess.TimeoutExpired:
        pass


def _group_alive(pgid):
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True  # (an unreaped zombie counts too: callers poll() the leader while waiting)


def tail(path, lines=15):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:]).rstrip() or "(empty)"
    except OSError:
        return "(no log)"


def screenshot(driver, path):
    """The whole page height at the window's width (1280 px), through the DevTools protocol; the
    W3C viewport screenshot as a fallback."""
    png = None
    try:
        metrics = driver.session_call("POST", "/goog/cdp/execute",
                                      {"cmd": "Page.getLayoutMetrics", "params": {}})
        size = metrics.get("cssContentSize") or metrics["contentSize"]
        view = metrics.get("cssLayoutViewport") or metrics["layoutViewport"]
        shot = driver.session_call("POST", "/goog/cdp/execute", {
            "cmd": "Page.captureScreenshot",
            "params": {"format": "png", "captureBeyondViewport": True,
                       "clip": {"x": 0, "y": 0, "width": view["clientWidth"],
                                "height": min(size["height"], 16000), "scale": 1}}})
        png = base64.b64decode(shot["data"])
    except (BrowserError, KeyError, TypeError, ValueError):
        png = base64.b64decode(driver.session_call("GET", "/screenshot"))
    with open(path, "wb") as f:
        f.write(png)


def resolve_report(target):
    path = os.path.abspath(target)
    if os.path.isdir(path):
        atlas_page = os.path.join(path, "atlas.html")
        run_page = os.path.join(path, "report.html")
        path = atlas_page if os.path.isfile(atlas_page) and not os.path.isfile(run_page) else run_page
    if not os.path.isfile(path):
        raise UsageError(f"no report at {path} (give a run, sweep or atlas folder, or its page)")
    return os.path.dirname(path), os.path.basename(path)


class Resources:
    """What check() starts; main() releases it with the overall timer off."""

    def __init__(self):
        self.server = self.proc = self.driver = None

    def release(self):
        if self.driver is not None and self.driver.session is not None:
            try:
                self.driver.request("DELETE", f"/session/{self.driver.session}", timeout=10)
            except Exception:  # noqa: BLE001 - the process group is ended below anyway
                pass
        stop_process_group(self.proc)
        if self.server is not None:
            self.server.shutdown()
            self.server.server_close()


def check(root, page, args, deadline, tmp, res):
    """Runs the browser checks; returns (problems, facts). Raises BrowserError/OverallTimeout.

    Everything started is recorded in res, which the caller releases."""
    seen, lock = [], threading.Lock()
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), make_handler(root, seen, lock))
    server.daemon_threads = True
    res.server = server
    threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.1},
                     daemon=True).start()
    res.proc, driver = start_chromedriver(tmp, deadline)
    res.driver = driver
    profile = os.path.join(tmp, "profile")
    os.makedirs(profile)
    capabilities = {"capabilities": {"alwaysMatch": {
        "browserName": "chrome",
        "pageLoadStrategy": "normal",
        "goog:chromeOptions": {"binary": CHROMIUM,
                               "args": CHROMIUM_ARGS + [f"--user-data-dir={profile}"]},
        "goog:loggingPrefs": {"browser": "ALL"},
    }}}
    status, value = driver.request("POST", "/session", capabilities)
    if status != 200 or not isinstance(value, dict) or "sessionId" not in value:
        message = value.get("message", value) if isinstance(value, dict) else value
        raise BrowserError(f"Chromium did not start (HTTP {status}): "
                           f"{str(message).strip()[:600]}\nchromedriver log:\n" +
                           tail(os.path.join(tmp, "chromedriver.log")))
    driver.session = value["sessionId"]
    facts = {}

    left_ms = int(max(1.0, deadline - time.monotonic() - 3) * 1000)
    driver.session_call("POST", "/timeouts", {"pageLoad": left_ms, "script": left_ms})
    try:
        driver.session_call("POST", "/window/rect", {"width": 1280, "height": 1024})
    except BrowserError:
        pass  # only affects the screenshot
    url = f"http://127.0.0.1:{server.server_address[1]}/{urllib.parse.quote(page)}"
    facts["url"] = url
    problems = []
    try:
        driver.session_call("POST", "/url", {"url": url})
    except BrowserError as e:
        problems.append(f"page did not load: {e}")
        return problems, facts

    # Wait for the document, then for every image to settle (complete is true also for a
    # broken image, so this ends quickly either way).
    page_facts = None
    while True:
        page_facts = driver.session_call("POST", "/execute/sync",
                                         {"script": PAGE_FACTS_JS, "args": []})
        settled = page_facts["readyState"] == "complete" and all(
            i["complete"] for i in page_facts["images"])
        if settled or time.monotonic() > deadline - 4:
            break
        time.sleep(0.1)
    time.sleep(0.2)  # let late console messages reach chromedriver
    log = driver.browser_log()
    facts.update(page_facts)
    facts["log"] = log

    if args.screenshot:
        try:
            screenshot(driver, args.screenshot)
            facts["screenshot"] = args.screenshot
        except (BrowserError, OSError, ValueError) as e:
            problems.append(f"screenshot not written: {e}")

    if page_facts["readyState"] != "complete":
        problems.append(f"document.readyState is still {page_facts['readyState']!r}")
    if not page_facts["title"].strip():
        problems.append("the page has no (or an empty) <title>")
    if page_facts["headings"] == 0:
        problems.append("the page has no <h1> or <h2>")
    broken = [i for i in page_facts["images"] if not i["complete"] or i["naturalWidth"] <= 0]
    for i in broken:
        state = "still loading" if not i["complete"] else "naturalWidth 0"
        problems.append(f"broken image: {i['src']} ({state})")
    for entry in log:
        if entry.get("level") == "SEVERE":
            problems.append(f"console SEVERE [{entry.get('source', '?')}]: "
                            f"{entry.get('message', '').strip()}")
    with lock:
        facts["requests"] = list(seen)
    for code, path in facts["requests"]:
        if code == 404 or code >= 400:
            problems.append(f"HTTP {code} from the server for {path}")
    return problems, facts


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="check_report.py",
        description="Check a granvv report.html in headless Chromium (title, headings, every "
                    "figure loaded, no SEVERE console message, no HTTP error).")
    parser.add_argument("report", help="a run folder (with report.html) or a report .html file")
    parser.add_argument("--screenshot", metavar="PNG", help="write a full-page screenshot here")
    parser.add_argument("--timeout", metavar="S", type=float, default=60.0,
                        help="overall time limit in seconds (default 60)")
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # argparse exits 2 on a usage error already; keep 0 for --help
        return e.code if isinstance(e.code, int) else EXIT_ERROR
    try:
        if not args.timeout > 0:
            raise UsageError(f"--timeout must be > 0 (got {args.timeout})")
        root, page = resolve_report(args.report)
        if args.screenshot:
            out_dir = os.path.dirname(os.path.abspath(args.screenshot))
            if not os.path.isdir(out_dir):
                raise UsageError(f"--screenshot: folder {out_dir} does not exist")
    except UsageError as e:
        print(f"check_report: usage error: {e}", file=sys.stderr)
        return EXIT_ERROR

    report = os.path.join(root, page)
    start = time.monotonic()
    deadline = start + args.timeout

    def on_alarm(signum, frame):
        raise OverallTimeout()

    previous = signal.signal(signal.SIGALRM, on_alarm)
    signal.setitimer(signal.ITIMER_REAL, args.timeout)
    tmp = tempfile.mkdtemp(prefix="granvv-check-report-")
    facts, res = {}, Resources()
    try:
        try:
            problems, facts = check(root, page, args, deadline, tmp, res)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
            res.release()
    except OverallTimeout:
        print(f"check_report: ERROR {report}: timed out after {args.timeout:g} s "
              "(browser start or page load hung)", file=sys.stderr)
        return EXIT_ERROR
    except BrowserError as e:
        print(f"check_report: ERROR {report}: browser could not be used: {e}", file=sys.stderr)
        return EXIT_ERROR
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    seconds = time.monotonic() - start
    images = facts.get("images", [])
    summary = (f"{len(images)} images, {len(facts.get('log', []))} console messages, "
               f"{len(facts.get('requests', []))} HTTP requests, {seconds:.1f} s")
    if problems:
        print(f"check_report: FAIL {report}: {len(problems)} problem(s) ({summary})")
        for p in problems:
            print(f"  - {p}")
    else:
        print(f"check_report: PASS {report} ({summary})")
    print(f"  title: {facts.get('title', '')!r}; h1/h2: {facts.get('headings', 0)}")
    for entry in facts.get("log", []):
        if entry.get("level") != "SEVERE":
            print(f"  console {entry.get('level')}: {entry.get('message', '').strip()}")
    if facts.get("screenshot"):
        print(f"  screenshot: {facts['screenshot']}")
    return EXIT_FAIL if problems else EXIT_PASS


if __name__ == "__main__":
    sys.exit(main())
