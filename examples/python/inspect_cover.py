"""Inspecting a cover: a node whose star a joint cuts in two, and the two physical covers on it.

    python3 examples/python/inspect_cover.py [OUT]      # writes OUT/cover.png (OUT: .)

In the NMM a mathematical cover (the star of triangles around a mesh node) that a joint crosses
is cut into physical covers, one per piece, each with its own displacement unknowns — which is
how the blocks on either side of a joint move apart:

        \\  star of node n  /          pieces on either side of the joint:
         \\______________/             physical covers i and j, both on node n
     joint  ~~~~~~~~~~~~~~~~~~~~~
           /              \\

1. cut data/jointed_slope.json (nmm.preprocess), or read its mesh file when given one;
2. find the first node with two physical covers (Mesh.cover_node counts them) off the base;
3. print each cover as nmm-inspect --cover shows it (Mesh.cover(i)), and check that the two
   covers share no element and that their elements are the elements of the node's triangles;
4. draw the mesh near the node twice, one cover outlined in each (nmm.plot.mesh).
Takes about a second.
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import nmm
import nmm.plot

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "data", "jointed_slope.json")


def main(out):
    mesh = nmm.preprocess(SCENE)                                     # 1.
    counts = np.bincount(mesh.cover_node, minlength=mesh.node_count)  # 2.
    inside = mesh.nodes[:, 1] >= 3 * mesh.mesh_size  # off the base, so the picture is all rock
    node = int(np.argmax((counts == 2) & inside))
    covers = np.flatnonzero(mesh.cover_node == node)
    print(f"{mesh}: {np.count_nonzero(counts > 1)} of {mesh.node_count} nodes carry more than one "
          f"physical cover; node {node} at {mesh.nodes[node]} carries {list(covers)}")
    shown = [mesh.cover(int(i)) for i in covers]                      # 3.
    for c in shown:
        print(f"  cover {c['index']}: body {c['body']}, elements {list(c['elements'])}, area {c['area']:.4f} m²")
    star = np.flatnonzero((mesh.triangles[mesh.element_triangle] == node).any(axis=1))
    together = np.sort(np.concatenate([c["elements"] for c in shown]))
    if set(shown[0]["elements"]) & set(shown[1]["elements"]) or not np.array_equal(together, star):
        raise SystemExit("the covers of the node do not split its star's elements")
    print(f"  their elements are the {len(star)} elements of node {node}'s star, split by the joint")

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.5), layout="constrained")  # 4.
    x, y = mesh.nodes[node]
    reach = 2.5 * mesh.mesh_size
    for ax, c in zip(axes, shown):
        nmm.plot.mesh(mesh, ax=ax, cover=c["index"], triangles=True)
        ax.set_xlim(x - reach, x + reach)
        ax.set_ylim(y - reach, y + reach)
    path = os.path.join(out, "cover.png")
    fig.savefig(path, dpi=120)
    print("wrote", path)


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    main(out)
