#!/usr/bin/env python3
"""Drives the console on a pseudo-terminal, through readline, as a user at a terminal does:
-i keeps the script's top-level locals; help on a table of the API and a search; Ctrl-C at the
continuation prompt drops the unfinished entry (and text typed on the line); Ctrl-C during a run
stops it with the model intact; Ctrl-D quits with status 0.
  console_terminal_test.py path/to/seismpm"""
import os
import pty
import select
import signal
import sys
import tempfile
import time

TIMEOUT = 60  # seconds for one answer (the sanitizer build is slow, CI's machine busy)


class Console:
    def __init__(self, argv, env):
        self.pid, self.fd = pty.fork()
        if self.pid == 0:
            os.execve(argv[0], argv, env)
        self.out = b""  # everything the console wrote
        self.seen = 0   # how much of it the checks have consumed

    def read_some(self, timeout):
        ready, _, _ = select.select([self.fd], [], [], timeout)
        if not ready:
            return False
        try:
            data = os.read(self.fd, 65536)
        except OSError:  # EIO: the child closed the terminal
            return False
        self.out += data
        return bool(data)

    def expect(self, text, what):
        """Waits for `text` after what was matched before; consumes up to its end."""
        deadline = time.time() + TIMEOUT
        needle = text.encode()
        while True:
            i = self.out.find(needle, self.seen)
            if i >= 0:
                before = self.out[self.seen:i].decode(errors="replace")
                self.seen = i + len(needle)
                return before
            if time.time() > deadline or not self.read_some(deadline - time.time()):
                late = time.time() > deadline
                if late or not self.alive():
                    fail(f"{what}: no '{text}' " + (f"within {TIMEOUT} s" if late else "(the console ended)"), self)

    def alive(self):
        pid, _ = os.waitpid(self.pid, os.WNOHANG)
        return pid == 0

    def send(self, text):
        os.write(self.fd, text.encode())

    def line(self, text):
        self.send(text + "\r")


def fail(message, console):
    print("FAIL:", message)
    print("--- terminal output ---")
    print(console.out.decode(errors="replace"))
    try:
        os.kill(console.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    sys.exit(1)


def main():
    binary = os.path.abspath(sys.argv[1])
    work = tempfile.mkdtemp(prefix="seismpm_console_terminal_")
    script = os.path.join(work, "scenario.lua")
    with open(script, "w") as f:
        f.write(
            "local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.01 }\n"
            "local soil = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }\n"
            "local block = m:body{ material = soil, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }\n"
            "m:fix{ side = \"bottom\" }\n")
    env = dict(os.environ, HOME=work, TERM="xterm", INPUTRC="/dev/null")
    c = Console([binary, "-i", script], env)

    # -i: the script's locals at the prompt.
    c.expect("locals kept for the console: m, soil, block", "-i")
    c.expect("seismpm> ", "first prompt")
    c.line("print(block:count(), m:count() == block:count())")
    c.expect("20000\ttrue", "a local of the script used at the prompt")
    c.expect("seismpm> ", "prompt")

    # help on a table of the API, and a search that finds nothing: text, no traceback.
    c.line("help(mpm.history)")
    listing = c.expect("seismpm> ", "help(mpm.history)")
    for part in ("mpm.history.csv", "mpm.history.at2", "history:at"):
        if part not in listing:
            fail(f"help(mpm.history) lists no {part}", c)
    c.line('help("quicksand")')
    answer = c.expect("seismpm> ", 'help("quicksand")')
    if "nothing in the API matches 'quicksand'" not in answer or "traceback" in answer:
        fail('help("quicksand") does not say that nothing matched', c)

    # Ctrl-C at the continuation prompt: the pending "m:" is dropped; the next line is an entry of its own.
    c.line("m:")
    c.expect(">> ", "continuation prompt")
    c.send("\x03")
    c.expect("seismpm> ", "a fresh prompt after Ctrl-C at >>")
    c.line("print('fresh', 6 * 7)")
    answer = c.expect("seismpm> ", "the entry after Ctrl-C")
    if "fresh\t42" not in answer:
        fail("the line after Ctrl-C at >> did not run as an entry of its own", c)
    # Ctrl-C with text typed on the line: the text is dropped too.
    c.send("print('dropped')")
    time.sleep(0.2)
    c.send("\x03")
    c.expect("seismpm> ", "a fresh prompt after Ctrl-C on a typed line")
    c.line("print('kept')")
    answer = c.expect("seismpm> ", "the entry after Ctrl-C on a typed line")
    if "kept\r\n" not in answer or "dropped\r\n" in c.out.decode(errors="replace"):
        fail("the text typed before Ctrl-C ran", c)

    # Ctrl-C during a run: stops at a step boundary, back at the prompt, the model intact.
    c.line("m:run{ duration = 1000 }")
    c.expect("] t = ", "the progress line of the run")  # the run is stepping: Ctrl-C now stops it
    c.send("\x03")
    c.expect("interrupted (Ctrl-C) at t =", "Ctrl-C during a run")
    c.expect("seismpm> ", "the prompt after an interrupted run")
    c.line("print('after', m:steps() > 0, block:count(), m:time() < 1000)")
    c.expect("after\ttrue\t20000\ttrue", "the model after the interrupted run")
    c.expect("seismpm> ", "prompt")

    c.send("\x04")  # Ctrl-D quits
    deadline = time.time() + TIMEOUT
    while time.time() < deadline:
        c.read_some(0.2)
        pid, status = os.waitpid(c.pid, os.WNOHANG)
        if pid:
            if os.waitstatus_to_exitcode(status) != 0:
                fail(f"exit status {os.waitstatus_to_exitcode(status)}", c)
            print("console terminal test passed")
            return
    fail("Ctrl-D did not end the console", c)


if __name__ == "__main__":
    main()
