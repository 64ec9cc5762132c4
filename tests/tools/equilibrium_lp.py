#!/usr/bin/python3
"""Does a compression-only equilibrium within friction exist? An independent LP.

    /usr/bin/python3 tests/tools/equilibrium_lp.py structure.json

Reads a JSON object written by a spec (blocks and the contact polygons found
by ashlar, nothing of ashlar's problem or solver):

    { "friction": mu (null: no sliding),
      "blocks": [ { "support": bool, "weight": N, "centroid": [x, y, z] }, ... ],
      "interfaces": [ { "a": i, "b": j (1-based), "normal": [..] (from a into b),
                        "u": [..], "v": [..], "vertices": [[x, y, z], ...] }, ... ] }

Per contact vertex a compression c >= 0 and friction f_u, f_v within the
four-sided pyramid |f_u| + |f_v| <= mu c (edges on the Coulomb cone, one
along u: the pyramid ashlar uses by default); the force acts on block b as
c n + f_u u + f_v v and its opposite on block a. Every free block must
balance its weight in force and in moment about its centroid. Slack
variables on those six rows (forces over the mean block weight, moments
over it times the mean block size) are minimised by HiGHS (through SciPy's
linprog): the optimum is 0 exactly when such an equilibrium exists.

Prints one JSON object: status (HiGHS's message), infeasibility (the optimum,
summed over blocks), stable (infeasibility below --tolerance, default
1e-6), the free blocks whose rows need slack (1-based, largest first) and
the problem's sizes. Needs Debian's python3-scipy and python3-numpy.
"""

import argparse
import json
import sys

try:
    import numpy
    import scipy.optimize
    import scipy.sparse
except ImportError:
    sys.exit("equilibrium_lp.py: scipy is missing: install it with "
             "'apt-get install python3-scipy python3-numpy' (run.sh does) "
             "and run this script with /usr/bin/python3")


def cross(p, q):
    return [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]


def solve(model, tolerance):
    blocks = model["blocks"]
    mu = model.get("friction")
    free = [i for i, b in enumerate(blocks) if not b["support"]]
    row_of = {block: 6 * k for k, block in enumerate(free)}
    weights = [blocks[i]["weight"] for i in free]
    mean_weight = sum(weights) / len(weights)
    sizes = [b.get("size", 1.0) for b in blocks]
    mean_size = sum(sizes[i] for i in free) / len(free)

    # Columns: per contact vertex c, f_u, f_v; then per balance row s+, s-.
    rows, cols, values = [], [], []          # equality rows
    g_rows, g_cols, g_values = [], [], []    # friction rows, <= 0
    columns = 0
    friction_rows = 0
    for contact in model["interfaces"]:
        a, b = contact["a"] - 1, contact["b"] - 1
        directions = [contact["normal"], contact["u"], contact["v"]]
        for point in contact["vertices"]:
            c, fu, fv = columns, columns + 1, columns + 2
            columns += 3
            if mu is not None:
                for su in (1.0, -1.0):
                    for sv in (1.0, -1.0):
                        g_rows += [friction_rows] * 3
                        g_cols += [fu, fv, c]
                        g_values += [su, sv, -mu]
                        friction_rows += 1
            for block, sign in ((b, 1.0), (a, -1.0)):
                if block not in row_of:
                    continue
                row = row_of[block]
                arm = [point[k] - blocks[block]["centroid"][k] for k in range(3)]
                for column, direction in zip((c, fu, fv), directions):
                    force = [sign * d / mean_weight for d in direction]
                    moment = [m / mean_size for m in cross(arm, force)]
                    for k in range(3):
                        rows += [row + k, row + 3 + k]
                        cols += [column, column]
                        values += [force[k], moment[k]]
    balance_rows = 6 * len(free)
    rhs = numpy.zeros(balance_rows)
    for k, block in enumerate(free):
        rhs[6 * k + 2] = blocks[block]["weight"] / mean_weight  # the forces carry the weight
    slack = columns
    for row in range(balance_rows):
        rows += [row, row]
        cols += [slack + 2 * row, slack + 2 * row + 1]
        values += [1.0, -1.0]
    total = slack + 2 * balance_rows
    A = scipy.sparse.csr_matrix((values, (rows, cols)), shape=(balance_rows, total))
    G = scipy.sparse.csr_matrix((g_values, (g_rows, g_cols)), shape=(friction_rows, total)) if friction_rows else None
    cost = numpy.zeros(total)
    cost[slack:] = 1.0
    bounds = []
    for k in range(slack // 3):
        bounds += [(0, None), (None, None), (None, None)]
    bounds += [(0, None)] * (2 * balance_rows)
    answer = scipy.optimize.linprog(cost, A_ub=G, b_ub=numpy.zeros(friction_rows) if friction_rows else None,
                                    A_eq=A, b_eq=rhs, bounds=bounds, method="highs",
                                    options={"primal_feasibility_tolerance": 1e-10,
                                             "dual_feasibility_tolerance": 1e-10})
    x = answer.x
    need = []
    if x is not None:
        for k, block in enumerate(free):
            amount = float(numpy.sum(x[slack + 12 * k: slack + 12 * k + 12]))
            if amount > tolerance:
                need.append((amount, block + 1))
    need.sort(reverse=True)
    infeasibility = max(0.0, float(answer.fun)) if x is not None else float("inf")
    return {
        "status": answer.message,
        "infeasibility": infeasibility,
        "stable": infeasibility <= tolerance,
        "failing_blocks": [block for _, block in need],
        "free_blocks": len(free),
        "interfaces": len(model["interfaces"]),
        "columns": total,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("path")
    parser.add_argument("--tolerance", type=float, default=1e-6)
    arguments = parser.parse_args()
    with open(arguments.path) as f:
        model = json.load(f)
    print(json.dumps(solve(model, arguments.tolerance)))


if __name__ == "__main__":
    main()
