"""Entry point of the render process: ``python -m arteleop.scene.render_child FD``.

A module of its own, which the package never imports, so that ``-m`` runs it fresh. Ctrl-C
reaches the whole process group: the parent stops this child, which ignores it.
"""

import signal
import sys
from multiprocessing.connection import Connection

from arteleop.scene.render_process import serve

if __name__ == "__main__":
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    serve(Connection(int(sys.argv[1])))
