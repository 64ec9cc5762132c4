#!/usr/bin/python3
"""Solves a QP given as a free-format QPS file with cvxopt; prints JSON.

    /usr/bin/python3 tests/tools/solve_qps.py problem.qps [--tolerance 1e-10]

Reads the sections NAME, ROWS, COLUMNS, RHS, BOUNDS, QUADOBJ and ENDATA
(objective 1/2 x^T Q x + c^T x with Q given by its lower triangle), turns
bounds into inequality rows and solves with cvxopt.solvers.qp on sparse
matrices. Prints one JSON object: status, objective, solve_seconds (cvxopt's
solve only, not reading the file), iterations and the problem's sizes.

An independent check of ashlar's own solver: it shares no code with ashlar,
so the two agreeing on the optimum means the export and the solver agree on
the problem. Needs Debian's python3-cvxopt and python3-numpy.
"""

import argparse
import json
import math
import sys
import time

try:
    import cvxopt
    import cvxopt.solvers
except ImportError:
    sys.exit("solve_qps.py: cvxopt is missing: install it with "
             "'apt-get install python3-cvxopt python3-numpy' (run.sh does) "
             "and run this script with /usr/bin/python3")

SECTIONS = {"NAME", "ROWS", "COLUMNS", "RHS", "BOUNDS", "QUADOBJ", "ENDATA"}
ROW_TYPES = {"N", "E", "G", "L"}


class QpsError(Exception):
    pass


class QuadraticProgram:
    """minimise 1/2 x^T Q x + c^T x + offset over rows of type E, G, L and bounds."""

    def __init__(self):
        self.name = ""
        self.objective_row = None
        self.row_type = {}          # row name -> "E", "G" or "L"
        self.row_order = []
        self.column_index = {}      # column name -> index
        self.linear = []            # c
        self.entries = []           # (row name, column index, value)
        self.rhs = {}               # row name -> value
        self.offset = 0.0
        self.lower = []
        self.upper = []
        self.quadratic = {}         # (i, j) with i >= j -> value

    def column(self, name):
        if name not in self.column_index:
            self.column_index[name] = len(self.linear)
            self.linear.append(0.0)
            self.lower.append(0.0)
            self.upper.append(math.inf)
        return self.column_index[name]


def read_qps(path):
    qp = QuadraticProgram()
    section = None
    with open(path) as file:
        for number, line in enumerate(file, 1):
            fields = line.split()
            if not fields or line.startswith("*"):
                continue
            where = f"{path}:{number}"
            if not line[0].isspace():
                section = fields[0]
                if section not in SECTIONS:
                    raise QpsError(f"{where}: section {section} is not supported "
                                   f"(only {', '.join(sorted(SECTIONS))})")
                if section == "NAME":
                    qp.name = " ".join(fields[1:])
                if section == "ENDATA":
                    break
                continue
            if section == "ROWS":
                read_row(qp, fields, where)
            elif section == "COLUMNS":
                read_column_entries(qp, fields, where)
            elif section == "RHS":
                read_rhs(qp, fields, where)
            elif section == "BOUNDS":
                read_bound(qp, fields, where)
            elif section == "QUADOBJ":
                read_quadratic(qp, fields, where)
            else:
                raise QpsError(f"{where}: data outside a section")
        else:
            raise QpsError(f"{path}: no ENDATA")
    if qp.objective_row is None:
        raise QpsError(f"{path}: no objective row (type N)")
    return qp


def number(text, where):
    try:
        return float(text)
    except ValueError:
        raise QpsError(f"{where}: '{text}' is not a number") from None


def read_row(qp, fields, where):
    if len(fields) != 2 or fields[0] not in ROW_TYPES:
        raise QpsError(f"{where}: expected '<N|E|G|L> name' in ROWS")
    kind, name = fields
    if kind == "N":
        if qp.objective_row is not None:
            raise QpsError(f"{where}: a second objective row {name}")
        qp.objective_row = name
    else:
        qp.row_type[name] = kind
        qp.row_order.append(name)


def read_column_entries(qp, fields, where):
    if len(fields) not in (3, 5):
        raise QpsError(f"{where}: expected 'column row value [row value]' in COLUMNS")
    column = qp.column(fields[0])
    for row, value in zip(fields[1::2], fields[2::2]):
        value = number(value, where)
        if row == qp.objective_row:
            qp.linear[column] += value
        elif row in qp.row_type:
            qp.entries.append((row, column, value))
        else:
            raise QpsError(f"{where}: unknown row {row}")


def read_rhs(qp, fields, where):
    # The set name is optional in free format: an odd count means it is there.
    pairs = fields[1:] if len(fields) % 2 == 1 else fields
    if not pairs or len(pairs) % 2:
        raise QpsError(f"{where}: expected '[set] row value [row value]' in RHS")
    for row, value in zip(pairs[0::2], pairs[1::2]):
        value = number(value, where)
        if row == qp.objective_row:
            qp.offset = -value  # MPS: the objective row's rhs is minus its constant
        elif row in qp.row_type:
            qp.rhs[row] = value
        else:
            raise QpsError(f"{where}: unknown row {row}")


def read_bound(qp, fields, where):
    kind = fields[0]
    valued = {"LO", "UP", "FX"}
    if kind not in valued | {"FR", "MI", "PL"}:
        raise QpsError(f"{where}: bound type {kind} is not supported")
    count = 4 if kind in valued else 3
    if len(fields) not in (count, count - 1):
        raise QpsError(f"{where}: expected '{kind} [set] column{' value' if kind in valued else ''}'")
    rest = fields[-(count - 2):]  # drop the optional bound set name
    if rest[0] not in qp.column_index:
        raise QpsError(f"{where}: unknown column {rest[0]}")
    column = qp.column_index[rest[0]]
    value = number(rest[1], where) if kind in valued else None
    if kind == "LO":
        qp.lower[column] = value
    elif kind == "UP":
        qp.upper[column] = value
    elif kind == "FX":
        qp.lower[column] = qp.upper[column] = value
    elif kind == "FR":
        qp.lower[column], qp.upper[column] = -math.inf, math.inf
    elif kind == "MI":
        qp.lower[column] = -math.inf
    else:
        qp.upper[column] = math.inf


def read_quadratic(qp, fields, where):
    if len(fields) != 3:
        raise QpsError(f"{where}: expected 'column column value' in QUADOBJ")
    for name in fields[:2]:
        if name not in qp.column_index:
            raise QpsError(f"{where}: unknown column {name}")
    i, j = (qp.column_index[name] for name in fields[:2])
    key = (max(i, j), min(i, j))
    qp.quadratic[key] = qp.quadratic.get(key, 0.0) + number(fields[2], where)


def sparse(triplets, rows, columns):
    values, row_indices, column_indices = (list(t) for t in zip(*triplets)) if triplets else ([], [], [])
    return cvxopt.spmatrix(values, row_indices, column_indices, (rows, columns), "d")


def cvxopt_matrices(qp):
    """P, q, G, h, A, b of cvxopt.solvers.qp: min 1/2 x'Px + q'x, Gx <= h, Ax = b."""
    n = len(qp.linear)
    p_entries = []
    for (i, j), value in qp.quadratic.items():
        p_entries.append((value, i, j))
        if i != j:
            p_entries.append((value, j, i))

    equality_index, inequality_index, inequality_sign = {}, {}, {}
    for row in qp.row_order:
        kind = qp.row_type[row]
        if kind == "E":
            equality_index[row] = len(equality_index)
        else:
            inequality_sign[row] = -1.0 if kind == "G" else 1.0  # a x >= r is -a x <= -r
            inequality_index[row] = len(inequality_index)
    a_entries, g_entries = [], []
    for row, column, value in qp.entries:
        if row in equality_index:
            a_entries.append((value, equality_index[row], column))
        else:
            g_entries.append((inequality_sign[row] * value, inequality_index[row], column))
    b = [qp.rhs.get(row, 0.0) for row in equality_index]
    h = [inequality_sign[row] * qp.rhs.get(row, 0.0) for row in inequality_index]

    for column in range(n):
        lower, upper = qp.lower[column], qp.upper[column]
        if lower == upper:
            a_entries.append((1.0, len(b), column))
            b.append(lower)
            continue
        if lower > -math.inf:
            g_entries.append((-1.0, len(h), column))
            h.append(-lower)
        if upper < math.inf:
            g_entries.append((1.0, len(h), column))
            h.append(upper)

    matrices = {
        "P": sparse(p_entries, n, n),
        "q": cvxopt.matrix(qp.linear, (n, 1), "d"),
        "G": sparse(g_entries, len(h), n),
        "h": cvxopt.matrix(h, (len(h), 1), "d"),
    }
    if b:
        matrices["A"] = sparse(a_entries, len(b), n)
        matrices["b"] = cvxopt.matrix(b, (len(b), 1), "d")
    return matrices


def objective_at(qp, x):
    value = qp.offset + sum(c * xi for c, xi in zip(qp.linear, x))
    for (i, j), q in qp.quadratic.items():
        value += q * x[i] * x[j] if i != j else 0.5 * q * x[i] * x[i]
    return value


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("qps", help="the QPS file")
    parser.add_argument("--tolerance", type=float, default=1e-10,
                        help="cvxopt's abstol, reltol and feastol (default 1e-10)")
    args = parser.parse_args()
    try:
        qp = read_qps(args.qps)
    except (OSError, QpsError) as error:
        sys.exit(f"solve_qps.py: {error}")
    matrices = cvxopt_matrices(qp)
    options = {"show_progress": False, "abstol": args.tolerance, "reltol": args.tolerance,
               "feastol": args.tolerance}
    start = time.perf_counter()
    solution = cvxopt.solvers.qp(options=options, **matrices)
    seconds = time.perf_counter() - start
    x = list(solution["x"]) if solution["x"] is not None else None
    print(json.dumps({
        "name": qp.name,
        "status": solution["status"],
        "objective": objective_at(qp, x) if x is not None else None,
        "solve_seconds": seconds,
        "iterations": solution["iterations"],
        "variables": len(qp.linear),
        "equalities": matrices["b"].size[0] if "b" in matrices else 0,
        "inequalities": matrices["h"].size[0],
        "primal_infeasibility": solution["primal infeasibility"],
        "dual_infeasibility": solution["dual infeasibility"],
    }))


if __name__ == "__main__":
    main()
