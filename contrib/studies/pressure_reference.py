"""Contact pressures against a converged model of the same scene.

A run's pairs come from its contact CSV (contact-0001.csv: x, area, pair
pressure, recovered pressure). The reference is the pair-pressure profile
of a converged run of the same model, linearly interpolated in x (zero
outside its pairs). Two distances, over the pairs with |x| at most twice
the reference half-width a_ref (the largest |x| of a loaded reference
pair; beyond, both pressures are zero):

- L2: sqrt(sum A_i (p_i - p_ref(x_i))^2 / sum A_i p_ref(x_i)^2), the
  pairs' tributary areas A_i as weights;
- largest: max |p_i - p_ref(x_i)| in units of the reference's peak."""

import csv
import math
import os


def read_pairs(folder, step=1):
    """(x, area, pressure, recovered pressure) of each pair of load step
    @p step of the run in @p folder, sorted by x."""
    path = os.path.join(folder, "contact-%04d.csv" % step)
    with open(path) as f:
        pairs = [(float(r["x"]), float(r["area"]), float(r["pressure"]),
                  float(r.get("recovered_pressure") or "nan"))
                 for r in csv.DictReader(f)]
    pairs.sort()
    return pairs


class Reference:
    """The pair-pressure profile of a converged run."""

    def __init__(self, pairs):
        self.profile = [(x, p) for x, _, p, _ in pairs]
        loaded = [abs(x) for x, p in self.profile if p > 0.]
        if not loaded:
            raise ValueError("the reference run has no loaded pair")
        self.half_width = max(loaded)
        self.peak = max(p for _, p in self.profile)

    def at(self, x):
        """The reference pressure at @p x (linear between its pairs)."""
        for (x0, p0), (x1, p1) in zip(self.profile, self.profile[1:]):
            if x0 <= x <= x1:
                return p0 + (p1 - p0) * (x - x0) / (x1 - x0) if x1 > x0 \
                    else p0
        return 0.

    def errors(self, pairs, column=2):
        """(L2, largest) of the pressures in @p column of @p pairs (2: the
        pair pressure, 3: the recovered one), see the module note."""
        num = den = largest = 0.
        for pair in pairs:
            x, area, p = pair[0], pair[1], pair[column]
            if abs(x) > 2. * self.half_width:
                continue
            q = self.at(x)
            num += area * (p - q) ** 2
            den += area * q ** 2
            largest = max(largest, abs(p - q))
        return math.sqrt(num / den), largest / self.peak
