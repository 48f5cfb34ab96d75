"""The Python examples of a Markdown page as one module, in their order
(each builds on the ones before, as a reader runs them), for mypy:

    python doc_examples.py docs/python.md > examples.py && mypy examples.py
"""

import re
import sys


def main():
    text = open(sys.argv[1], encoding="utf-8").read()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    if not blocks:
        sys.exit(f"{sys.argv[1]}: no Python examples")
    print("\n".join(blocks))


if __name__ == "__main__":
    main()
