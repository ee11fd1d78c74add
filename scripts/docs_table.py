"""Generated blocks of the docs: a Markdown file holds a generated table between its markers, checked or written.

The markers are lines of their own, `<!-- NAME: begin ... -->` and `<!-- NAME: end -->`. scripts/fpga_budget.py and
scripts/fpga_latency.py keep their tables in docs/fpga.md this way (add_output_arguments(), output()); from the
command line, the lines between
the markers must equal a table file (a test's output, e.g. tests/fpga/hls_access_check.cc's):

  docs_table.py --name NAME --table FILE --docs MARKDOWN [--update]

Exit 0 when they are equal (or after --update), 1 with a diff when they differ, 2 when a file or marker is missing.
"""
import argparse
import difflib
import os
import re
import sys
import tempfile


class MissingMarkers(Exception):
    pass


def sync(docs_path, name, generated, update):
    """None when the block NAME of docs_path equals `generated` (after writing it there, with update), else a diff.
    Raises MissingMarkers, or OSError."""
    with open(docs_path, encoding="utf-8") as f:
        docs = f.read()
    found = re.search(rf"^<!-- {re.escape(name)}: begin.*-->\n(.*?)^<!-- {re.escape(name)}: end -->$", docs,
                      re.S | re.M)
    if not found:
        raise MissingMarkers(f"{docs_path} has no lines <!-- {name}: begin ... --> ... <!-- {name}: end -->")
    if found[1] == generated:
        return None
    if update:
        with tempfile.NamedTemporaryFile("w", encoding="utf-8", dir=os.path.dirname(os.path.abspath(docs_path)),
                                         delete=False) as f:
            f.write(docs[:found.start(1)] + generated + docs[found.end(1):])
        os.replace(f.name, docs_path)
        return None
    return "".join(difflib.unified_diff(found[1].splitlines(True), generated.splitlines(True), "documented",
                                        "generated"))


def add_output_arguments(parser, what):
    """A script's options for its generated `what`: --markdown, --docs FILE, --update-docs FILE, one at most (the
    group returned, for more)."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--markdown", action="store_true", help=f"print the {what}")
    group.add_argument("--docs", help=f"check that this Markdown file holds the {what}")
    group.add_argument("--update-docs", help=f"write the {what} into this Markdown file")
    return group


def output(args, name, generate, what):
    """What the options of add_output_arguments ask for, of the block NAME that generate() returns: the exit status
    (0, or 1 with a diff printed), or None when none of them was given."""
    if args.markdown:
        print(generate(), end="")
        return 0
    if not (args.update_docs or args.docs):
        return None
    diff = sync(args.update_docs or args.docs, name, generate(), bool(args.update_docs))
    if diff:
        print(f"{args.docs}: the {what} differ from the generated ones (--update-docs):\n{diff}", end="")
        return 1
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--name", required=True)
    parser.add_argument("--table", required=True)
    parser.add_argument("--docs", required=True)
    parser.add_argument("--update", action="store_true", help="write the table into the docs")
    args = parser.parse_args()
    try:
        with open(args.table, encoding="utf-8") as f:
            diff = sync(args.docs, args.name, f.read(), args.update)
    except (OSError, MissingMarkers) as e:
        print(f"docs_table.py: {e}", file=sys.stderr)
        return 2
    if diff is None:
        return 0
    print(diff, end="")
    print(f"{args.docs} differs from {args.table}: rerun the test, then docs_table.py --update with the same arguments")
    return 1


if __name__ == "__main__":
    sys.exit(main())
