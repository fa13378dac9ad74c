"""The bundles' Debian sources (resources/debian_sources.sh): when the first
suite's archive does not serve a source package whole, the next suite's is
taken, and the script says so.

The archive is this machine's Debian mirror seen through a proxy of the
test's own, which answers 404 to the first request for each package's .dsc,
as the archive did for trixie's and forky's on 2026-12-07. Everything else
(the signed indexes, the other suite's files) passes through unchanged, so
apt checks them as usual. Needs root (apt-get as root) and the mirror.

On a trixie or forky machine (CI's chroots) the installed libpolyclipping-dev
is not bookworm's: the fallback must not look for the installed version's
source, which bookworm lacks (as it once did)."""
import http.server
import os
import re
import subprocess
import threading
import urllib.error
import urllib.request

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "resources", "debian_sources.sh")
HELD = "Held back by the test"


def mirror():
    return subprocess.run(["sh", "-c", ". resources/apt.sh && mirror"], cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout.strip()


class Proxy(http.server.ThreadingHTTPServer):
    """Forwards GETs to the mirror; 404s the first .dsc asked of each package."""

    def __init__(self, upstream):
        self.upstream = upstream.rstrip("/")
        self.held = []    # the .dsc files answered 404
        self.served = []  # the pool files passed through
        self.lock = threading.Lock()
        super().__init__(("127.0.0.1", 0), Handler)


class Handler(http.server.BaseHTTPRequestHandler):
    def log_message(self, *args):
        pass

    def do_GET(self):
        server = self.server
        name = self.path.rsplit("/", 1)[-1]
        if name.endswith(".dsc"):
            package = name.split("_")[0]
            with server.lock:
                first = all(not h.startswith(package + "_") for h in server.held)
                if first:
                    server.held.append(name)
            if first:
                self.send_error(404, HELD)
                return
        try:
            host = re.match(r"^https?://[^/]+", server.upstream).group(0)
            with urllib.request.urlopen(host + self.path, timeout=60) as r:
                body = r.read()
                status = r.status
        except urllib.error.HTTPError as e:
            self.send_error(e.code, str(e.reason))
            return
        if "/pool/" in self.path:
            with server.lock:
                server.served.append(name)
        self.send_response(status)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


@pytest.fixture
def proxy():
    if os.geteuid() != 0:
        pytest.skip("apt-get source with a package list of its own runs as root")
    server = Proxy(mirror())
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield server
    server.shutdown()
    server.server_close()


def fetch(dest, suites, mirror_url, *packages):
    env = dict(os.environ, PLUNGE_SOURCE_SUITES=suites, PLUNGE_SOURCE_MIRROR=mirror_url)
    return subprocess.run(["sh", SCRIPT, str(dest), *packages], env=env, capture_output=True, text=True,
                          timeout=600)


def test_the_first_suite_missing_a_file_falls_back_to_the_next(proxy, tmp_path):
    port = proxy.server_address[1]
    upstream_path = re.sub(r"^https?://[^/]+", "", proxy.upstream)
    run = fetch(tmp_path / "src", "trixie bookworm", "http://127.0.0.1:%d%s" % (port, upstream_path),
                "libpolyclipping", "muparser")
    assert run.returncode == 0, run.stdout + run.stderr
    lines = run.stdout.splitlines()
    # Each package: the first suite's failure said, with the file and the answer, then the fallback.
    for package, source in (("libpolyclipping", "libpolyclipping"), ("muparser", "muparser")):
        said = [l for l in lines if l.startswith("sources: %s:" % package)]
        assert len(said) == 2, lines
        assert "trixie's archive does not serve its source whole" in said[0], said
        assert re.search(r"\(%s_[^ ]+\.dsc: 404 %s\)" % (source, HELD), said[0]), said
        assert "trying the next suite" in said[0]
        assert re.fullmatch(r"sources: %s: Debian's %s \S+, from bookworm" % (package, source), said[1]), said
    assert len(proxy.held) == 2 and all(h.endswith(".dsc") for h in proxy.held), proxy.held
    # What was taken is recorded, and is bookworm's: its .dsc was passed through, and unpacked.
    origin = [l.split() for l in (tmp_path / "src" / "ORIGIN").read_text().splitlines()]
    assert [(o[0], o[1], o[3]) for o in origin] == [("libpolyclipping", "libpolyclipping", "bookworm"),
                                                    ("muparser", "muparser", "bookworm")]
    for _, source, version, _ in origin:
        assert "%s_%s.dsc" % (source, version) in proxy.served
    assert list((tmp_path / "src").glob("libpolyclipping-*/cpp/clipper.cpp"))
    assert list((tmp_path / "src").glob("muparser-*/src/muParserBase.cpp"))
    assert not (tmp_path / "src" / ".apt").exists()


def test_no_suite_serving_it_is_an_error_naming_the_package(proxy, tmp_path):
    port = proxy.server_address[1]
    upstream_path = re.sub(r"^https?://[^/]+", "", proxy.upstream)
    # One suite only: the proxy holds back its .dsc, and there is nothing to fall back on.
    run = fetch(tmp_path / "src", "bookworm", "http://127.0.0.1:%d%s" % (port, upstream_path), "muparser")
    assert run.returncode != 0
    assert run.stderr.strip().splitlines() == [
        "sources: no suite of bookworm serves muparser's source whole (mirror http://127.0.0.1:%d%s)"
        % (port, upstream_path)]
    assert not (tmp_path / "src" / "ORIGIN").exists()


def test_the_order_of_the_suites():
    def order(codename):
        return subprocess.run(["sh", SCRIPT, "--suites-for", codename], capture_output=True, text=True,
                              check=True).stdout.split()
    assert order("bookworm") == ["bookworm"]
    assert order("trixie") == ["trixie", "bookworm"]
    assert order("forky") == ["forky", "trixie", "bookworm"]
    assert order("duke") == ["duke", "forky", "trixie", "bookworm"]
