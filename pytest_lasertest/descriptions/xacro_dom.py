"""xacro's two DOM edits, `replace_node` and `remove_previous_comments`, in linear time.

xacro replaces a macro call, an include or a `<xacro:if>` with its content by inserting each
new node with minidom's insertBefore, and after each such directive moves one blank text node
with insertBefore and removeChild. Both look nodes up among a parent's children from the start
every time: quadratic in the children, about a minute for 80,000. Here new nodes go in with one
slice assignment, and each lookup starts just before where the previous one in that parent ended
(xacro works through a parent's children in order), so every description the guard lets through
expands in seconds. The nodes, and the links between them, come out as xacro's own would.
"""

from __future__ import annotations

from typing import Any

# xacro's DOM (xml.dom.minidom) has no type hints.
Node = Any
_BACK = 16  # how far before the last edit a lookup starts: the comments before a directive


class Splicer:
    """The edits of one expansion, remembering where in each parent the last one was."""

    def __init__(self, blank: Node) -> None:
        self.blank = blank  # xacro's blank text node, which marks comments as kept
        self.hints: dict[int, int] = {}  # id of a parent -> index of its last edit

    def replace(self, node: Node, by: Node, content_only: bool) -> None:
        """`node` replaced by `by` (a node, a list of them, or None), or by their children when
        `content_only`: what xacro.xmlutils.replace_node does."""
        new = _detached(by, content_only, self)
        parent = node.parentNode
        siblings = parent.childNodes
        index = self._index(parent, node)
        siblings[index : index + 1] = new
        self.hints[id(parent)] = index + len(new)
        _link(parent, siblings, index, len(new))
        node.parentNode = node.previousSibling = node.nextSibling = None

    def remove_previous_comments(self, node: Node) -> None:
        """xacro's remove_previous_comments: the comments just before a directive go with it,
        and the blank node after it keeps the comments before the next one."""
        after, previous = node.nextSibling, node.previousSibling
        while previous is not None:
            if _is_blank_line(previous):
                previous = previous.previousSibling
            if previous is not None and previous.nodeType == previous.COMMENT_NODE:
                comment, previous = previous, previous.previousSibling
                self.remove(comment)
            else:
                if after is not None and after is not self.blank:
                    self.insert_before(self.blank, after)
                return

    def remove(self, child: Node) -> None:
        """`child` taken out of its parent."""
        parent = child.parentNode
        index = self._index(parent, child)
        del parent.childNodes[index]
        self.hints[id(parent)] = index
        _link(parent, parent.childNodes, index, 0)
        child.parentNode = child.previousSibling = child.nextSibling = None

    def insert_before(self, new: Node, reference: Node) -> None:
        """`new` taken from where it was and put before `reference`."""
        if new.parentNode is not None:
            self.remove(new)
        parent = reference.parentNode
        index = self._index(parent, reference)
        parent.childNodes.insert(index, new)
        self.hints[id(parent)] = index + 1
        _link(parent, parent.childNodes, index, 1)

    def _index(self, parent: Node, node: Node) -> int:
        siblings = parent.childNodes
        start = max(0, min(self.hints.get(id(parent), 0), len(siblings)) - _BACK)
        try:
            return int(siblings.index(node, start))
        except ValueError:  # before the hint, or a hint left by a parent of the same id
            return int(siblings.index(node))


def _is_blank_line(node: Node) -> bool:
    return bool(
        node.nodeType == node.TEXT_NODE and node.data.isspace() and node.data.count("\n") <= 1
    )


def _detached(by: Node, content_only: bool, splicer: Splicer) -> list[Node]:
    """The nodes that go in, each taken from where it was."""
    items = [] if by is None else by if isinstance(by, list) else [by]
    new: list[Node] = []
    for item in items:
        if content_only:
            new += list(item.childNodes)
            item.childNodes[:] = []
        else:
            if item.parentNode is not None:
                splicer.remove(item)
            new.append(item)
    return new


def _link(parent: Node, siblings: list[Node], index: int, count: int) -> None:
    """Parent and sibling links for the `count` nodes now at `index`, and their neighbours."""
    before = siblings[index - 1] if index else None
    end = index + count
    after = siblings[end] if end < len(siblings) else None
    for child in siblings[index:end]:
        child.parentNode = parent
        child.previousSibling = before
        if before is not None:
            before.nextSibling = child
        before = child
    if before is not None:
        before.nextSibling = after
    if after is not None:
        after.previousSibling = before
