"""The verdict the repository's checkers (scripts/check_docs.py, check_layers.py,
check_scheme_names.py) end with: each problem on a line of its own on stdout, then
`failed` on stderr and exit status 1; or, with no problem, `clean` and 0."""
import sys


def report(problems, failed, clean):
    for p in problems:
        print(p)
    if problems:
        print(failed, file=sys.stderr)
        return 1
    print(clean)
    return 0
