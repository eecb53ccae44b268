"""Entry point of the render process: ``python -m arteleop.scene.render_child FD``.

A module of its own, which the package never imports, so that ``-m`` runs it fresh. The parent
starts it in a process group of its own and stops it; it ignores Ctrl-C all the same, should
someone send it one.
"""

import signal
import sys
from multiprocessing.connection import Connection

from arteleop.scene.render_process import serve

if __name__ == "__main__":
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    serve(Connection(int(sys.argv[1])))
