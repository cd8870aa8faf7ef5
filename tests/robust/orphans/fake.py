#!/usr/bin/python3
"""A program that will not end by itself (installed by ../check as gmsh and as
bwrap): it ignores SIGTERM, SIGINT and SIGHUP, drops the death signal it was
given (PR_SET_PDEATHSIG), and leaves a process behind in a session of its own
by a double fork, the way a daemon does: that process is in no group of
contact2d's and its parent is gone.  The file `mode` beside it says what it
does then: `hang` (sleep) or `exit` (exit 0 at once, the process left behind
still running).  When both run, it writes its pid to `ready`.  As bwrap it
answers the sandbox probe (`bwrap ... true`) with exit 0."""
import ctypes
import os
import signal
import sys
import time

here = os.path.dirname(os.path.abspath(sys.argv[0]))
if os.path.basename(sys.argv[0]) == "bwrap" and sys.argv[-1] == "true":
    sys.exit(0)
libc = ctypes.CDLL(None, use_errno=True)


def harden():
    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, signal.SIG_IGN)
    libc.prctl(1, 0, 0, 0, 0)               # PR_SET_PDEATHSIG, 0: no death signal


harden()
with open(os.path.join(here, "mode")) as f:
    mode = f.read().strip()
r, w = os.pipe()
if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        harden()
        os.write(w, b"x")
        time.sleep(300)
        os._exit(0)
    os._exit(0)
os.close(w)
os.read(r, 1)
os.wait()
with open(os.path.join(here, "ready.tmp"), "w") as f:
    f.write(str(os.getpid()))
os.rename(os.path.join(here, "ready.tmp"), os.path.join(here, "ready"))
if mode == "exit":
    sys.exit(0)
time.sleep(300)
