"""`python3 -m quadcover ARGS...` runs the quadcover command-line tool (info, field, param, remesh, metrics, render)."""
from quadcover._cli import main

if __name__ == "__main__":
    main()
