"""Per-module summary of a mutmut run (`make mutation`).

Reads the output of ``mutmut results --all true`` (lines ``    NAME: STATUS``)
and prints, per mutated module, how many mutants were killed, survived, timed
out or had no test, then the names of the survivors. Mutant names are
``<module>.x_<function>__mutmut_<n>`` (methods: ``<module>.xǁ<Class>ǁ<method>...``).
``mutmut show NAME`` prints the diff of one of them.
"""

from __future__ import annotations

import re
import sys
from collections import Counter, defaultdict

NAME = re.compile(r"^\s*(?P<name>(?P<module>[\w.]+?)\.x[_ǁ]\S*__mutmut_\d+):\s*(?P<status>.+?)\s*$")


def main(path: str) -> int:
    counts: dict[str, Counter] = defaultdict(Counter)
    survivors: dict[str, list[str]] = defaultdict(list)
    unparsed = 0
    with open(path, encoding="utf-8") as f:
        for line in f:
            if not line.strip():
                continue
            m = NAME.match(line)
            if m is None:
                unparsed += 1
                continue
            module, status = m["module"], m["status"]
            counts[module][status] += 1
            if status == "survived":
                survivors[module].append(m["name"])
    if not counts:
        print(f"{path}: no mutant results found", file=sys.stderr)
        return 1
    statuses = sorted({s for c in counts.values() for s in c})
    width = max(len(m) for m in counts)
    print(f"{'module':<{width}}  " + "  ".join(f"{s:>9}" for s in statuses) + "      total")
    for module in sorted(counts):
        c = counts[module]
        print(f"{module:<{width}}  " + "  ".join(f"{c[s]:>9}" for s in statuses) + f"  {sum(c.values()):>9}")
    total = Counter()
    for c in counts.values():
        total.update(c)
    print(f"{'all':<{width}}  " + "  ".join(f"{total[s]:>9}" for s in statuses) + f"  {sum(total.values()):>9}")
    for module in sorted(survivors):
        print(f"\nsurvived in {module}:")
        for name in survivors[module]:
            print(f"  {name}")
    if unparsed:
        print(f"\n({unparsed} lines not understood)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "mutants/results.txt"))
