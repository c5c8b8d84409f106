"""INTERIM: replaced at merge by the findings work of issue 23."""
from __future__ import annotations
from dataclasses import dataclass
import numpy as np
from .measurement import clipped_samples


@dataclass(frozen=True)
class Finding:
    kind: str
    message: str
    record: str
    where: str
    skew_s: float | None = None
    excluded: np.ndarray | None = None
    unsafe_for: tuple = ()

    def as_json(self):
        return {"kind": self.kind, "message": self.message, "record": self.record, "where": self.where}


def find_data_problems(record, *, exclude_clipped=None):
    c = clipped_samples(record.force)
    if c.any() and exclude_clipped is not False:
        return [Finding("clipped", f"{int(c.sum())} clipped", record.name, "", excluded=c)]
    return []


def excluded_mask(findings, n):
    m = np.zeros(n, bool)
    for f in findings:
        if f.excluded is not None:
            m |= f.excluded
    return m
