"""mkdocs hooks: the pairs-file reference page is written from the JSON Schema at build time, and
the site serves the schema itself, for editors to point at.

mkdocs loads this file by path (mkdocs.yml, `hooks:`); it is excluded from the pages."""

from __future__ import annotations

from typing import Any

from mkdocs.structure.files import File, Files

from pytest_lasertest.pairsfile.schema import pairs_file_schema, schema_text
from pytest_lasertest.reports.reference import schema_reference

MARKER = "<!-- lasertest: pairs-file schema -->"
SCHEMA_FILE = "pairs-file.schema.json"


def on_files(files: Files, config: Any, **_: Any) -> Files:
    """The site's files and the schema at its root, which pages may link to."""
    files.append(File.generated(config, SCHEMA_FILE, content=schema_text()))
    return files


def on_page_markdown(markdown: str, **_: Any) -> str:
    """The page with the generated reference where its marker stands; the reference is made
    only for the page that has one."""
    if MARKER not in markdown:
        return markdown
    return markdown.replace(MARKER, schema_reference(pairs_file_schema()))
