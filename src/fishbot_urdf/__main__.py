"""`python -m fishbot_urdf` runs the `fishbot` command."""

from .cli import main

main()
