"""A task module that stops Python as it is imported: a study naming it gets a message."""

import sys

sys.exit("this module ends the program")
