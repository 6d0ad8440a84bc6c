"""How a page's excerpt is held against a command's output (`shown.py`): its lines must appear
together and in order, `...` standing for any text, and a page's blocks are found by kind."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.docs.shown import Shown, contains, examples, unchecked_text_blocks

OUTPUT = """\
============================= test session starts ==============================
platform linux -- Python 3.11.7, pytest-9.2.0, pluggy-1.7.0
collected 5 items

gate.lasertest.yaml c.Fps                                                [100%]
= 1 failed, 1 passed, 1 skipped in 207.43s (0:03:27) =
"""


@pytest.mark.parametrize(
    "excerpt",
    [
        "collected 5 items",
        "platform linux -- Python ...\ncollected 5 items",
        "collected 5 items   \n\ngate.lasertest.yaml c.Fps ... [100%]",  # trailing spaces aside
        "collected 5 items\n...\n= 1 failed, 1 passed, 1 skipped in ... =",
        "============================= test session starts ===...\n...\ncollected 5 items",
        "",
    ],
)
def test_an_excerpt_whose_lines_appear_together_matches(excerpt: str) -> None:
    assert contains(OUTPUT, excerpt)


@pytest.mark.parametrize(
    "excerpt",
    [
        "collected 6 items",
        "platform linux -- Python ...\ngate.lasertest.yaml c.Fps ...",  # lines left out between
        "collected 5 items\ngate.lasertest.yaml ...",  # the blank line between left out
        "collected 5",  # part of a line, without `...`
        "= 1 failed, 1 passed, 1 skipped in ...s =\ncollected 5 items",  # out of order
    ],
)
def test_an_excerpt_that_is_not_in_the_output_does_not_match(excerpt: str) -> None:
    assert not contains(OUTPUT, excerpt)


PAGE = """\
# A page

```text
$ lasertest catalogue
model ...
$ lasertest doctor
```

<!-- shown-output: lasertest catalogue -->
```text
hokuyo_ust_10lx ...
```

<!-- shown-file: gate.lasertest.yaml -->
```yaml
robot: husky
```

<!-- not-output: a sketch -->
```
tree/
```

```
an output nobody checks
```

```python
print("code, not output")
```
"""


def test_a_pages_sessions_directives_and_unchecked_output_blocks_are_told_apart(
    tmp_path: Path,
) -> None:
    page = tmp_path / "page.md"
    page.write_text(PAGE)
    found = [example.parsed for example in examples(page)]
    assert found[0] == [
        Shown("lasertest catalogue", "model ...\n", fresh=True),
        Shown("lasertest doctor", "", fresh=True),
    ]
    assert found[1] == [Shown("lasertest catalogue", "hokuyo_ust_10lx ...\n", fresh=False)]
    assert (found[2].name, found[2].text) == ("gate.lasertest.yaml", "robot: husky\n")
    assert len(found) == 3
    assert unchecked_text_blocks(page) == [24]
