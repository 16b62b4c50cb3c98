#!/usr/bin/env python3
"""A rolling restart of a halfcast fleet under load, measured (docs/serving.md, "Restarts and
upgrades").

N worlds (`halfcast serve --proxy-protocol`, one shared host key) behind HAProxy with the shipped
snippet (docs/deploy/haproxy-halfcast.cfg: its ports moved, a server line per world, a stats
socket in `global` as Debian's haproxy.cfg has); P OpenSSH players who stay, and who reconnect
after the wait their farewell names when their world restarts; a new OpenSSH login every 200 ms
that plays a moment and leaves. Then each world is restarted in turn as the documented upgrade
loop does it: SIGTERM, wait until HAProxy's runtime API (`show servers state`) has it down (so
no drain, however short, is over before HAProxy stopped sending it players), wait until the
process has exited (the drain), start it again, wait until HAProxy has it up, then the next.
Prints the logins that failed of how many (and why), each world's drain seconds, how long
HAProxy took to take it out and back, and the players' reconnects.

Needs python3, haproxy, ssh (OpenSSH) and a built halfcast (the shell loop in docs/serving.md
needs socat instead of this script's own socket code). Runs from any working directory; the
worlds, HAProxy and the players' ssh processes it started are stopped when it ends, fails, or
gets Ctrl-C or SIGTERM. Every player comes from 127.0.0.1, so the worlds' per-address limits are
raised (--max-per-ip, --max-startups-per-ip); behind a real balancer each player has an address
of their own.

    python3 docs/deploy/fleet_restart.py --halfcast target/release/halfcast --worlds 3
"""

import argparse
import fcntl
import os
import pty
import re
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import termios
import threading
import time

# The repository: this file is docs/deploy/fleet_restart.py.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Every process this script started, stopped on the way out (see `cleanup`).
STARTED = set()
STARTED_LOCK = threading.Lock()


def started(proc):
    """Remembers `proc` for `cleanup`; returns it."""
    with STARTED_LOCK:
        STARTED.add(proc)
    return proc


def finished(proc):
    """Kills `proc` (if it still runs), reaps it and forgets it."""
    if proc.poll() is None:
        proc.kill()
    proc.wait()
    with STARTED_LOCK:
        STARTED.discard(proc)


def forget(proc):
    """`proc` has ended by itself: nothing to stop."""
    with STARTED_LOCK:
        STARTED.discard(proc)


def cleanup():
    """Stops whatever this script started and is still running: SIGTERM, then SIGKILL."""
    with STARTED_LOCK:
        procs = list(STARTED)
    for p in procs:
        if p.poll() is None:
            p.terminate()
    deadline = time.time() + 5
    for p in procs:
        try:
            p.wait(max(0.1, deadline - time.time()))
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


def on_signal(signum, _frame):
    """Ctrl-C or SIGTERM: leave through `cleanup`."""
    sys.exit(128 + signum)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class World:
    """One `halfcast serve` process; started again on the same ports."""

    def __init__(self, n, args, hk, dir):
        self.n, self.args, self.hk, self.dir = n, args, hk, dir
        self.ssh, self.metrics = free_port(), free_port()
        self.proc = None
        self.starts = 0

    def start(self):
        self.starts += 1
        log = open(os.path.join(self.dir, f"world{self.n}.{self.starts}.log"), "w")
        cmd = [self.args.halfcast, "serve", "--listen", f"127.0.0.1:{self.ssh}",
               "--proxy-protocol", "--metrics", f"127.0.0.1:{self.metrics}",
               "--host-key", self.hk, "--db", "none",
               "--drain-seconds", str(self.args.drain_seconds),
               "--round-minutes", str(self.args.round_minutes),
               "--max-sessions", str(self.args.max_sessions),
               "--max-per-ip", "200", "--max-startups-per-ip", "60"]
        self.proc = started(subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=log,
                                             stderr=log))
        deadline = time.time() + 30
        while time.time() < deadline:
            try:
                socket.create_connection(("127.0.0.1", self.metrics), timeout=1).close()
                return
            except OSError:
                time.sleep(0.05)
        sys.exit(f"world {self.n} did not start")


def haproxy_config(worlds, front, sock):
    snippet = open(os.path.join(ROOT, "docs/deploy/haproxy-halfcast.cfg")).read()
    snippet = snippet.replace("bind :22\n", f"bind 127.0.0.1:{front}\n")
    snippet = snippet.replace("    bind :::22 v6only\n", "")
    lines = [l for l in snippet.splitlines() if not l.strip().startswith("server world")]
    lines += [f"    server world{w.n} 127.0.0.1:{w.ssh} port {w.metrics}" for w in worlds]
    return ("global\n    maxconn 4096\n"
            f"    stats socket {sock} mode 600 level admin\n\n"
            "defaults\n    mode http\n    timeout connect 5s\n    timeout client 50s\n"
            "    timeout server 50s\n\n" + "\n".join(lines) + "\n")


def servers_up(sock):
    """World names HAProxy has up (srv_op_state 2), from its runtime API."""
    try:
        with socket.socket(socket.AF_UNIX) as s:
            s.connect(sock)
            s.sendall(b"show servers state halfcast_worlds\n")
            data = b""
            while chunk := s.recv(65536):
                data += chunk
    except OSError:
        return set()
    up = set()
    for line in data.decode().splitlines():
        f = line.split()
        if len(f) > 5 and f[1] == "halfcast_worlds" and f[5] == "2":
            up.add(f[3])
    return up


def ssh(front, user):
    """`ssh` in an 80x24 pty, as a player runs it; (process, pty master)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
    env = dict(os.environ, TERM="xterm-256color")
    env.pop("COLORTERM", None)
    p = started(subprocess.Popen(
        ["ssh", "-tt", "-F", "/dev/null", "-p", str(front), "-o", "StrictHostKeyChecking=no",
         "-o", "UserKnownHostsFile=/dev/null", "-o", "BatchMode=yes", "-o", "LogLevel=ERROR",
         "-o", "ConnectTimeout=20", f"{user}@127.0.0.1"],
        stdin=slave, stdout=slave, stderr=slave, env=env, start_new_session=True))
    os.close(slave)
    return p, master


# A game screen is kilobytes; a refusal ("server full", a closed connection) a line or two. The
# game's header is drawn with cursor moves between its words, so its text is not looked for.
PLAYING_BYTES = 4000


def read_some(master, timeout):
    import select
    r, _, _ = select.select([master], [], [], timeout)
    if not r:
        return b""
    try:
        return os.read(master, 65536) or None
    except OSError:
        return None


def login(front, user, patience):
    """One login that plays a moment and leaves; None, or why it failed."""
    p, master = ssh(front, user)
    seen = b""
    deadline = time.time() + patience
    try:
        while time.time() < deadline:
            chunk = read_some(master, 0.2)
            if chunk is None:
                return "closed before playing: " + tail(seen)
            seen += chunk
            if len(seen) >= PLAYING_BYTES:
                return None
        return "not playing after %.0f s: %s" % (patience, tail(seen))
    finally:
        finished(p)
        os.close(master)


def tail(b):
    text = re.sub(r"\x1b\[[0-9;?]*[A-Za-z]", " ", b.decode(errors="replace"))
    return " ".join(text.split())[-200:]


class Player(threading.Thread):
    """Stays; when its world restarts, waits what the farewell says, and comes back."""

    def __init__(self, front, name, stop):
        super().__init__(daemon=True)
        self.front, self.name, self.stop = front, name, stop
        self.sessions = self.failures = self.told = 0
        self.waits = []
        self.playing = False

    def run(self):
        while not self.stop.is_set():
            p, master = ssh(self.front, self.name)
            seen, got, played = b"", 0, False
            while True:
                chunk = read_some(master, 0.5)
                if chunk is None or self.stop.is_set():
                    break
                got += len(chunk)
                seen = (seen + chunk)[-4000:]
                if not played and got >= PLAYING_BYTES:
                    played, self.playing = True, True
                    self.sessions += 1
            finished(p)
            os.close(master)
            self.playing = False
            if self.stop.is_set():
                return
            if not played:
                self.failures += 1
            m = re.search(rb"reconnect to continue in (\d+) s", seen)
            wait = int(m.group(1)) if m else 1
            if m:
                self.told += 1
                self.waits.append(wait)
            self.stop.wait(wait)


def main():
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    try:
        run()
    finally:
        cleanup()


def run():
    ap = argparse.ArgumentParser()
    ap.add_argument("--halfcast", default=os.path.join(ROOT, "target/release/halfcast"))
    ap.add_argument("--worlds", type=int, default=2)
    ap.add_argument("--players", type=int, default=24)
    ap.add_argument("--login-every", type=float, default=0.2)
    ap.add_argument("--round-minutes", type=float, default=10)
    ap.add_argument("--drain-seconds", type=int, default=30)
    ap.add_argument("--max-sessions", type=int, default=32)
    ap.add_argument("--settle", type=float, default=10)
    args = ap.parse_args()
    dir = tempfile.mkdtemp(prefix="fleet-restart-")
    hk = os.path.join(dir, "hk")
    worlds = [World(n + 1, args, hk, dir) for n in range(args.worlds)]
    for w in worlds:
        w.start()
    front, sock = free_port(), os.path.join(dir, "admin.sock")
    cfg = os.path.join(dir, "haproxy.cfg")
    open(cfg, "w").write(haproxy_config(worlds, front, sock))
    hap = started(subprocess.Popen(["haproxy", "-db", "-f", cfg], stdout=subprocess.DEVNULL,
                                   stderr=open(os.path.join(dir, "haproxy.log"), "w")))
    names = {f"world{w.n}" for w in worlds}
    while servers_up(sock) != names:
        time.sleep(0.2)
    stop = threading.Event()
    players = [Player(front, f"p{i}", stop) for i in range(args.players)]
    for p in players:
        p.start()
        time.sleep(0.05)
    while sum(p.playing for p in players) < args.players:
        time.sleep(0.2)
    print(f"{args.players} players in, logs in {dir}", flush=True)

    logins, lock, probes = [], threading.Lock(), []
    probing = threading.Event()

    def prober():
        i = 0
        while not probing.is_set():
            i += 1
            started = time.time()

            def one(k=i, at=started):
                r = login(front, f"login{k}", 30)
                with lock:
                    logins.append((at, r))

            t = threading.Thread(target=one, daemon=True)
            t.start()
            probes.append(t)
            probing.wait(max(0.0, args.login_every - (time.time() - started)))

    probe_loop = threading.Thread(target=prober, daemon=True)
    probe_loop.start()
    time.sleep(args.settle)
    t0 = time.time()
    report = []
    for w in worlds:
        sent = time.time()
        w.proc.send_signal(signal.SIGTERM)
        # HAProxy must have taken the world out before it counts as restarted: a drain shorter
        # than its checks (fall 2, inter 2s) would otherwise be over before HAProxy noticed,
        # and "up" afterwards would say nothing.
        while f"world{w.n}" in servers_up(sock):
            time.sleep(0.1)
        out = time.time() - sent
        w.proc.wait()
        forget(w.proc)
        drained = time.time() - sent
        w.start()
        began = time.time()
        while f"world{w.n}" not in servers_up(sock):
            time.sleep(0.1)
        back = time.time() - began
        report.append((w.n, drained, back))
        print(f"world {w.n}: HAProxy had it out {out:.1f} s after SIGTERM, drained in "
              f"{drained:.1f} s, HAProxy had it back {back:.1f} s after it started", flush=True)
    time.sleep(args.settle)
    probing.set()
    probe_loop.join()
    for t in probes:
        t.join()
    end = time.time()
    stop.set()
    done = logins
    during = [(at, r) for at, r in done if t0 <= at]
    failed = [(at, r) for at, r in done if r is not None]
    print(f"logins: {len(failed)} failed of {len(done)} ({len(during)} from the first SIGTERM "
          f"on, over {end - t0:.0f} s)")
    for at, r in failed:
        print(f"  failed at +{at - t0:.1f} s: {r}")
    told = sum(p.told for p in players)
    print(f"players: {told} told to reconnect (waits {min(sum((p.waits for p in players), []) or [0])}"
          f"-{max(sum((p.waits for p in players), []) or [0])} s), "
          f"{sum(p.sessions for p in players)} sessions, {sum(p.failures for p in players)} "
          "reconnects that did not get to play")
    print("drains: " + ", ".join(f"world {n} {d:.1f} s" for n, d, _ in report))


if __name__ == "__main__":
    main()
