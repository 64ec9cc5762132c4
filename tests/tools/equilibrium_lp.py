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
over it times the mean block size) are minimised by GLPK's simplex method
(through cvxopt): the optimum is 0 exactly when such an equilibrium exists.

Prints one JSON object: status (cvxopt's for GLPK's), infeasibility (the optimum,
summed over blocks), stable (infeasibility below --tolerance, default
1e-6), the free blocks whose rows need slack (1-based, largest first) and
the problem's sizes. Needs Debian's python3-cvxopt and python3-numpy.
"""

import argparse
import json
import sys

try:
    import cvxopt
    import cvxopt.solvers
except ImportError:
    sys.exit("equilibrium_lp.py: cvxopt is missing: install it with "
             "'apt-get install python3-cvxopt python3-numpy' (run.sh does) "
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

    equality = {}  # (row, column) -> value
    rhs = [0.0] * (6 * len(free))
    columns = 0
    inequality = []  # (row, column, value)
    inequality_rows = 0
    for contact in model["interfaces"]:
        a, b = contact["a"] - 1, contact["b"] - 1
        directions = [contact["normal"], contact["u"], contact["v"]]
        for point in contact["vertices"]:
            c, fu, fv = columns, columns + 1, columns + 2
            columns += 3
            inequality.append((inequality_rows, c, -1.0))  # c >= 0
            inequality_rows += 1
            if mu is not None:
                for su in (1.0, -1.0):
                    for sv in (1.0, -1.0):
                        inequality.append((inequality_rows, fu, su))
                        inequality.append((inequality_rows, fv, sv))
                        inequality.append((inequality_rows, c, -mu))
                        inequality_rows += 1
            for block, sign in ((b, 1.0), (a, -1.0)):
                if block not in row_of:
                    continue
                row = row_of[block]
                arm = [point[k] - blocks[block]["centroid"][k] for k in range(3)]
                for column, direction in zip((c, fu, fv), directions):
                    force = [sign * d / mean_weight for d in direction]
                    moment = [m / mean_size for m in cross(arm, force)]
                    for k in range(3):
                        equality[(row + k, column)] = equality.get((row + k, column), 0.0) + force[k]
                        equality[(row + 3 + k, column)] = equality.get((row + 3 + k, column), 0.0) + moment[k]
    for k, block in enumerate(free):
        rhs[6 * k + 2] = blocks[block]["weight"] / mean_weight  # the forces carry the weight
    # Slack: row + s_plus - s_minus, both >= 0, minimised.
    slack = columns
    rows = 6 * len(free)
    for row in range(rows):
        equality[(row, slack + 2 * row)] = 1.0
        equality[(row, slack + 2 * row + 1)] = -1.0
        for column in (slack + 2 * row, slack + 2 * row + 1):
            inequality.append((inequality_rows, column, -1.0))
            inequality_rows += 1
    total = slack + 2 * rows
    cost = cvxopt.matrix([0.0] * slack + [1.0] * (2 * rows))
    A = cvxopt.spmatrix([v for v in equality.values()], [r for r, _ in equality], [c for _, c in equality],
                        (rows, total))
    G = cvxopt.spmatrix([v for _, _, v in inequality], [r for r, _, _ in inequality],
                        [c for _, c, _ in inequality], (inequality_rows, total))
    h = cvxopt.matrix([0.0] * inequality_rows)
    # GLPK's presolver and tight bounds: without them its simplex method has
    # stopped "optimal" at a vertex whose slack was 0.005 above the optimum.
    cvxopt.solvers.options["glpk"] = {"msg_lev": "GLP_MSG_OFF", "presolve": "GLP_ON",
                                      "tol_bnd": 1e-10, "tol_dj": 1e-10}
    answer = cvxopt.solvers.lp(cost, G, h, A, cvxopt.matrix(rhs), solver="glpk")
    x = answer["x"]
    need = []
    for k, block in enumerate(free):
        amount = sum(x[slack + 2 * row] + x[slack + 2 * row + 1] for row in range(6 * k, 6 * k + 6))
        if amount > tolerance:
            need.append((amount, block + 1))
    need.sort(reverse=True)
    infeasibility = max(0.0, answer["primal objective"]) if x is not None else float("inf")
    return {
        "status": answer["status"],
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
