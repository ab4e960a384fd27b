"""The `dynslam` command of a pip-installed package: the C++ command shipped beside it."""
import os
import sys

from ._sweep_tools import find_cli


def main():
    command = find_cli()
    os.execv(command, [command, *sys.argv[1:]])
