"""What the docs' figure scripts share (docs/kgd_curves.py, docs/cohesive_beam.py,
docs/crack_paths.py): their command line, BIN_DIR OUT_DIR [--figure PATH] (the figure goes to
OUT_DIR/<name>.svg unless --figure names it), and an SVG page on a white background, written
with one line per element.
"""
import argparse
import pathlib


def arguments(extra=()):
    """The parsed command line and OUT_DIR, made if missing. extra: (flag, add_argument keywords)
    pairs a script adds."""
    ap = argparse.ArgumentParser()
    ap.add_argument("bin_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--figure", default=None)
    for flag, kw in extra:
        ap.add_argument(flag, **kw)
    a = ap.parse_args()
    out = pathlib.Path(a.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return a, out


def figure_path(a, out, name):
    """Where the figure goes: --figure, else OUT_DIR/name."""
    return pathlib.Path(a.figure) if a.figure else out / name


def page(width, height, font_size):
    """The opening elements of a page width × height (px): the svg element and its background."""
    return [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" '
            f'font-size="{font_size}">', f'<rect width="{width}" height="{height}" fill="white"/>']


def write(parts, path):
    """Closes the page and writes it to path."""
    path.write_text("\n".join(parts + ["</svg>"]) + "\n")
