"""The Signorini-Coulomb complementarity problem of the time-stepping scheme, solved by enumerating its cases.

The contact law of the Stewart-Trinkle / Anitescu-Potra scheme (docs/references.md) for the compass biped of 002
(Gamus & Or 2015) Secs. 4-5: impulses with 0 <= P_n _|_ v_n+ - floor >= 0 and the Coulomb cone with maximal
dissipation, per contact free, sticking or sliding either way; one contact in closed form, two (the plastic heel
strike, 002 Sec. 4.1) by enumeration; and how far a contact is from leaving its case.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from mjpoincare.analysis.theory.compass_biped_friction.time_stepping_model import Matrix, Vector

#: Relative tolerance of the complementarity conditions (case selection of the enumeration).
LCP_TOL = 1e-10
#: Case labels of one contact: ("free", "stick", "slip+", "slip-"); slip+ is forward (downhill) sliding.
CASES = ("free", "stick", "slip+", "slip-")


def coulomb_contacts(delassus: Matrix, v0: Vector, mu: float, floor: Vector) -> tuple[Vector, tuple[str, ...]]:
    """Impulses P (2k,) = (P_t, P_n) per contact solving, with v+ = v0 + W P (contact velocities, rows (t, n) per
    contact; W the Delassus matrix J M^-1 J^T): 0 <= P_n _|_ v_n+ - floor >= 0, |P_t| <= mu P_n, v_t+ = 0 while
    |P_t| < mu P_n, P_t = -mu P_n sgn(v_t+) while sliding. Every combination of the cases :data:`CASES` is tried
    and the solutions are compared; ValueError if none or two different ones exist (no consistent contact state:
    Painleve's paradox, not expected here)."""
    k = v0.size // 2
    if k == 1:
        return _one_contact(delassus, v0, mu, float(floor[0]))
    eye = np.eye(2 * k)
    found: list[tuple[Vector, tuple[str, ...]]] = []
    cases_allowed = CASES if math.isfinite(mu) else CASES[:2]
    for cases in itertools.product(cases_allowed, repeat=k):
        rows: list[Vector] = []
        rhs: list[float] = []
        for i, case in enumerate(cases):
            t, n = 2 * i, 2 * i + 1
            if case == "free":
                rows += [eye[t], eye[n]]
                rhs += [0.0, 0.0]
            elif case == "stick":
                rows += [delassus[t], delassus[n]]
                rhs += [-v0[t], floor[i] - v0[n]]
            else:
                rows += [eye[t] + (mu if case == "slip+" else -mu) * eye[n], delassus[n]]
                rhs += [0.0, floor[i] - v0[n]]
        try:
            p = np.linalg.solve(np.array(rows), np.array(rhs))
        except np.linalg.LinAlgError:
            continue
        v = v0 + delassus @ p
        tol_v = LCP_TOL * (1.0 + float(np.max(np.abs(v0))))
        tol_p = LCP_TOL * (1.0 + float(np.max(np.abs(p))))
        ok = True
        for i, case in enumerate(cases):
            pt, pn, vt, vn = p[2 * i], p[2 * i + 1], v[2 * i], v[2 * i + 1]
            if case == "free":
                ok = ok and vn >= floor[i] - tol_v
            elif case == "stick":
                ok = ok and pn >= -tol_p and (math.isinf(mu) or abs(pt) <= mu * pn + tol_p)
            else:
                ok = ok and pn >= -tol_p and (1.0 if case == "slip+" else -1.0) * vt >= -tol_v
        if ok:
            found.append((p, cases))
    if not found:
        raise ValueError("no consistent contact state (Signorini-Coulomb problem without solution)")
    p, cases = found[0]
    for other, _ in found[1:]:
        if not np.allclose(other, p, rtol=1e-8, atol=1e-12):
            raise ValueError("two contact states solve the Signorini-Coulomb problem (non-unique)")
    return p, cases


def _one_contact(delassus: Matrix, v0: Vector, mu: float, floor: float) -> tuple[Vector, tuple[str, ...]]:
    """:func:`coulomb_contacts` for one contact, the cases in closed form (the stance steps' fast path)."""
    (wtt, wtn), (wnt, wnn) = (float(x) for x in delassus[0]), (float(x) for x in delassus[1])
    vt0, vn0 = float(v0[0]), float(v0[1])
    tol_v = LCP_TOL * (1.0 + max(abs(vt0), abs(vn0)))
    found: list[tuple[float, float, str]] = []
    if vn0 >= floor - tol_v:
        found.append((0.0, 0.0, "free"))
    det = wtt * wnn - wtn * wnt
    pt = (-vt0 * wnn - wtn * (floor - vn0)) / det
    pn = (wtt * (floor - vn0) + wnt * vt0) / det
    tol_p = LCP_TOL * (1.0 + max(abs(pt), abs(pn)))
    if pn >= -tol_p and (math.isinf(mu) or abs(pt) <= mu * pn + tol_p):
        found.append((pt, pn, "stick"))
    if math.isfinite(mu):
        for case, s in (("slip+", 1.0), ("slip-", -1.0)):
            pn = (floor - vn0) / (wnn - s * mu * wnt)
            vt = vt0 + (wtn - s * mu * wtt) * pn
            if pn >= -LCP_TOL * (1.0 + abs(pn)) and s * vt >= -tol_v:
                found.append((-s * mu * pn, pn, case))
    if not found:
        raise ValueError("no consistent contact state (Signorini-Coulomb problem without solution)")
    pt, pn, case = found[0]
    for other_t, other_n, _ in found[1:]:
        if not (math.isclose(other_t, pt, rel_tol=1e-8, abs_tol=1e-12)
                and math.isclose(other_n, pn, rel_tol=1e-8, abs_tol=1e-12)):
            raise ValueError("two contact states solve the Signorini-Coulomb problem (non-unique)")
    return np.array([pt, pn]), (case,)


def case_margin(delassus: Matrix, v0: Vector, mu: float, floor: float, case: str) -> float:
    """How far one contact forced into ``case`` is from leaving it (>= 0 inside; the zero is the switch): v_n+ -
    floor when free, min(P_n, mu P_n - |P_t|) when sticking, the sliding speed s v_t+ when slipping."""
    (wtt, wtn), (wnt, wnn) = (float(x) for x in delassus[0]), (float(x) for x in delassus[1])
    vt0, vn0 = float(v0[0]), float(v0[1])
    if case == "free":
        return vn0 - floor
    if case == "stick":
        det = wtt * wnn - wtn * wnt
        pt = (-vt0 * wnn - wtn * (floor - vn0)) / det
        pn = (wtt * (floor - vn0) + wnt * vt0) / det
        return min(pn, mu * pn - abs(pt))
    s = 1.0 if case == "slip+" else -1.0
    pn = (floor - vn0) / (wnn - s * mu * wnt)
    return s * (vt0 + (wtn - s * mu * wtt) * pn)
