"""Reading a study file that may be hostile, in bounded time and memory.

A study file may come from someone else, and cablestudy runs on shared machines. Before
any of it becomes Python objects, the text is held to these limits, each refused with a
message naming the line (``line: path: what; allowed ...``):

- its size (:data:`DEFAULT_MAX_BYTES`, set by ``--max-study-size`` or the environment
  variable :data:`SIZE_ENV`), checked before it is read in full;
- UTF-8 text without control characters (the byte offset of the first bad byte);
- lists and mappings nested at most :data:`MAX_DEPTH` deep;
- at most :data:`MAX_NODES` YAML nodes once aliases are expanded: the composer keeps
  the expanded size of every anchored node, so an alias costs one addition and a
  document that would cross the budget ("billion laughs") is refused at that alias,
  before anything is expanded; an alias inside its own anchor is refused too;
- only the standard tags (``!!str``, ``!!int``, ``!!float``, ``!!bool``, ``!!null``,
  ``!!seq``, ``!!map``): no Python objects, no local tags;
- each key once per mapping (the key and both lines are named).
"""

from __future__ import annotations

import os
import re
from typing import Any

import yaml
from yaml.composer import Composer
from yaml.constructor import ConstructorError, SafeConstructor
from yaml.resolver import Resolver

if yaml.__with_libyaml__:  # libyaml's parser: events about 7 times faster than PyYAML's
    from yaml._yaml import CParser as _EventParser
else:  # pragma: no cover - PyYAML built without libyaml

    class _EventParser(yaml.reader.Reader, yaml.scanner.Scanner, yaml.parser.Parser):  # type: ignore[no-redef]
        def __init__(self, stream: str) -> None:
            yaml.reader.Reader.__init__(self, stream)
            yaml.scanner.Scanner.__init__(self)
            yaml.parser.Parser.__init__(self)


Loc = tuple[str | int, ...]

MAX_NODES = 100_000
"""YAML nodes (values, keys, lists, mappings) a study may have after expanding aliases."""
MAX_DEPTH = 32
"""Lists and mappings a value may be nested in."""
DEFAULT_MAX_BYTES = 1 << 20
"""Default size limit of a study file [bytes]: 1 MiB, some 400 times the largest example."""
SIZE_ENV = "CABLESTUDY_MAX_STUDY_SIZE"
"""Environment variable that sets the size limit (``--max-study-size`` overrides it)."""

_CORE = "tag:yaml.org,2002:"
STANDARD_TAGS = tuple(f"{_CORE}{t}" for t in ("str", "int", "float", "bool", "null", "seq", "map"))
_ALLOWED_TAGS = ", ".join(f"!!{t[len(_CORE) :]}" for t in STANDARD_TAGS)
# what YAML allows in a stream (printable characters, tab and line breaks)
_NON_PRINTABLE = re.compile(
    "[^\x09\x0a\x0d\x20-\x7e\x85\xa0-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]"
)
_SHOWN = 20  # duplicate keys listed one by one
_SIZE = re.compile(r"^\s*([0-9]+)\s*([kKmMgG]?)(?:i?[bB])?\s*$")
_UNITS = {"": 1, "k": 1 << 10, "m": 1 << 20, "g": 1 << 30}


class YamlRefused(ValueError):
    """Study text refused before it was turned into data; ``problems`` are messages
    ``line: path: what; allowed ...`` (without the file name)."""

    def __init__(self, problems: list[str]) -> None:
        self.problems = list(problems)
        super().__init__("\n".join(self.problems))


def dotted(loc: Loc) -> str:
    """A YAML path as the study file spells it (``line.segments.0.length``)."""
    return ".".join(str(p) for p in loc) if loc else "<top>"


def printable(message: str) -> str:
    """``message`` with every unprintable character escaped (``\\r``, ``\\x1b``): a key
    or value from the file can neither break a message across lines nor send control
    sequences to the user's terminal."""
    if message.isprintable():
        return message
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in message)


def parse_size(text: str) -> int:
    """Bytes in a size such as ``1048576``, ``512k``, ``4M``, ``4MiB`` or ``1G`` (powers
    of 1024). Raises ValueError naming what is allowed."""
    match = _SIZE.match(text)
    if match is None or int(match[1]) < 1:
        raise ValueError(f"must be a size in bytes such as 1048576, 512k, 4M or 1G (got {text!r})")
    return int(match[1]) * _UNITS[match[2].lower()]


def max_study_bytes() -> int:
    """The size limit of a study file [bytes]: :data:`SIZE_ENV` if set, else the default."""
    raw = os.environ.get(SIZE_ENV)
    if raw is None or not raw.strip():
        return DEFAULT_MAX_BYTES
    try:
        return parse_size(raw)
    except ValueError as exc:
        raise YamlRefused([f"0: environment variable {SIZE_ENV}: {exc}"]) from None


def too_large(size: int, limit: int, exact: bool) -> str:
    """The message for a study file over the size limit."""
    got = f"{size} bytes" if exact else f"more than {limit} bytes"
    return (
        f"1: <top>: the study file is larger than the size limit; allowed: at most "
        f"{limit} bytes (raise it with --max-study-size or {SIZE_ENV}) (got {got})"
    )


def _short(tag: str) -> str:
    return "!!" + tag[len(_CORE) :] if tag.startswith(_CORE) else tag


def _clip(value: object, n: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= n else text[: n - 3] + "..."


class StudyLoader(_EventParser, Composer, SafeConstructor, Resolver):
    """Safe YAML loader for study files: libyaml's parser (when PyYAML has it), PyYAML's
    composer with the module's limits enforced node by node, PyYAML's safe constructor.
    It also reads ``1e-9`` and ``2E5`` as numbers (YAML 1.2; PyYAML follows YAML 1.1, which
    needs a dot in the mantissa and would return a string).

    ``stream`` is the study text; the limits are the module's :data:`MAX_NODES` (after
    alias expansion) and :data:`MAX_DEPTH`.
    """

    def __init__(self, stream: str):
        _EventParser.__init__(self, stream)
        Composer.__init__(self)
        SafeConstructor.__init__(self)
        Resolver.__init__(self)
        self.duplicates: list[str] = []
        self._nodes = 0  # nodes of the expanded document so far
        self._depth = 0
        self._loc: Loc = ()
        self._sizes: dict[str, tuple[int, int]] = {}  # anchor -> (expanded nodes, line)
        self._open: set[str] = set()  # anchors whose node is being composed
        self._keys: list[dict[str, int]] = []  # keys seen in each open mapping -> line

    # ------------------------------------------------------------- composing
    # PyYAML's composer, not libyaml's: its nodes pass through compose_node below
    check_node = Composer.check_node
    get_node = Composer.get_node
    get_single_node = Composer.get_single_node

    def compose_node(self, parent: yaml.Node | None, index: Any) -> yaml.Node:
        saved = self._loc
        if parent is None:
            loc = saved
        elif isinstance(index, int):
            loc = saved + (index,)
        elif isinstance(index, yaml.ScalarNode):
            loc = saved + (str(index.value),)
            self._check_duplicate(index, loc)
        else:  # a mapping key: reported at its mapping
            loc = saved
        self._loc = loc
        try:
            event = self.peek_event()
            line = event.start_mark.line + 1
            if isinstance(event, yaml.AliasEvent):
                self._count_alias(event.anchor, loc, line)
                return Composer.compose_node(self, parent, index)
            tag = getattr(event, "tag", None)
            if tag is not None and tag != "!" and tag not in STANDARD_TAGS:
                raise YamlRefused(
                    [
                        f"{line}: {dotted(loc)}: YAML tag {_short(tag)!r} is not allowed; "
                        f"allowed: no tag, or a standard tag: {_ALLOWED_TAGS}"
                    ]
                )
            start = self._nodes
            self._nodes += 1
            if self._nodes > MAX_NODES:
                raise YamlRefused(
                    [
                        f"{line}: {dotted(loc)}: the study has more than {MAX_NODES} YAML "
                        f"nodes (values, keys, lists and mappings, aliases expanded); "
                        f"allowed: at most {MAX_NODES}"
                    ]
                )
            mapping = isinstance(event, yaml.MappingStartEvent)
            collection = mapping or isinstance(event, yaml.SequenceStartEvent)
            if collection:
                self._depth += 1
                if self._depth > MAX_DEPTH:
                    raise YamlRefused(
                        [
                            f"{line}: {dotted(loc)}: lists and mappings nested more than "
                            f"{MAX_DEPTH} deep; allowed: at most {MAX_DEPTH} levels"
                        ]
                    )
            if mapping:
                self._keys.append({})
            anchor = event.anchor
            if anchor is not None:
                self._open.add(anchor)
            node = Composer.compose_node(self, parent, index)
            if anchor is not None:
                self._open.discard(anchor)
                self._sizes[anchor] = (self._nodes - start, line)
            if mapping:
                self._keys.pop()
            if collection:
                self._depth -= 1
            return node
        finally:
            self._loc = saved

    def _count_alias(self, anchor: str, loc: Loc, line: int) -> None:
        if anchor in self._open:
            raise YamlRefused(
                [
                    f"{line}: {dotted(loc)}: the alias *{anchor} lies inside the node it "
                    "names (an endless document); allowed: aliases to a complete node "
                    "given earlier"
                ]
            )
        if anchor not in self._sizes:
            return  # PyYAML reports the undefined alias
        size, anchor_line = self._sizes[anchor]
        self._nodes += size
        if self._nodes > MAX_NODES:
            raise YamlRefused(
                [
                    f"{line}: {dotted(loc)}: the alias *{anchor} (anchor &{anchor} on line "
                    f"{anchor_line}: {size} nodes) would expand the study past "
                    f"{MAX_NODES} YAML nodes; allowed: at most {MAX_NODES} nodes "
                    f"with aliases expanded (got at least {self._nodes})"
                ]
            )

    def _check_duplicate(self, key: yaml.ScalarNode, loc: Loc) -> None:
        if not self._keys:
            return
        seen = self._keys[-1]
        name = str(key.value)
        line = key.start_mark.line + 1
        if name in seen:
            self.duplicates.append(
                f"{line}: {dotted(loc)}: duplicate key {_clip(name)} (first given on line "
                f"{seen[name]}, again on line {line}); allowed: each key once per mapping"
            )
        else:
            seen[name] = line

    # ---------------------------------------------------------- constructing
    def construct_object(self, node: yaml.Node, deep: bool = False) -> Any:
        """As PyYAML's, but a scalar its tag cannot read (``!!int abc``, the date
        2024-13-45, an integer of 5000 digits) is a YAML error at its line."""
        try:
            return super().construct_object(node, deep)
        except yaml.YAMLError:
            raise
        except (ValueError, TypeError, KeyError, OverflowError) as exc:
            raise ConstructorError(
                None,
                None,
                f"cannot read {_clip(node.value)} as {_short(node.tag)} ({exc})",
                node.start_mark,
            ) from None


StudyLoader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(
        r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
        |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
        |\.[0-9_]+(?:[eE][-+]?[0-9]+)?
        |[-+]?\.(?:inf|Inf|INF)
        |\.(?:nan|NaN|NAN))$""",
        re.X,
    ),
    list("-+0123456789."),
)


def _control_character(text: str) -> str | None:
    """The message for the first character YAML does not allow in a stream (or None)."""
    bad = _NON_PRINTABLE.search(text)
    if bad is None:
        return None
    pos = bad.start()
    line = text.count("\n", 0, pos) + 1
    offset = len(text[:pos].encode("utf-8", "surrogatepass"))
    return (
        f"{line}: the study file has the control character U+{ord(bad[0]):04X} at byte "
        f"{offset}; allowed: printable text, tabs and line breaks"
    )


def _yaml_error(exc: yaml.YAMLError) -> str:
    """``line: not valid YAML: what (while parsing what, from line n)``."""
    problem = getattr(exc, "problem", None)
    mark = getattr(exc, "problem_mark", None) or getattr(exc, "context_mark", None)
    line = mark.line + 1 if mark is not None else 1
    if problem is None:
        return f"{line}: not valid YAML: {exc}"
    context = getattr(exc, "context", None)
    where = getattr(exc, "context_mark", None)
    if context:
        problem += f" ({context}" + (f" from line {where.line + 1})" if where else ")")
    return f"{line}: not valid YAML: {problem}"


def compose_and_load(text: str) -> tuple[yaml.Node | None, Any]:
    """Parse one YAML document within the limits: (node graph with marks, data).

    Raises :class:`YamlRefused` with one message per fault."""
    bad = _control_character(text)
    if bad is not None:
        raise YamlRefused([bad])
    try:
        loader = StudyLoader(text)
    except yaml.YAMLError as exc:
        raise YamlRefused([_yaml_error(exc)]) from None
    try:
        node = loader.get_single_node()
        if loader.duplicates:
            shown = loader.duplicates[:_SHOWN]
            more = len(loader.duplicates) - len(shown)
            if more:
                line = loader.duplicates[_SHOWN].split(":", 1)[0]
                shown.append(f"{line}: <top>: and {more} more duplicate keys, not shown")
            raise YamlRefused(shown)
        data = loader.construct_document(node) if node is not None else None
    except yaml.YAMLError as exc:
        message = _yaml_error(exc)
        if "maximum nesting depth" in message:
            # the YAML reader's own nesting limit (libyaml since PyYAML 6.0.4, far above
            # ours) tripped while scanning ahead, before the composer saw the levels
            line = message.split(":", 1)[0]
            message = (
                f"{line}: {dotted(loader._loc)}: lists and mappings nested more than "
                f"{MAX_DEPTH} deep; allowed: at most {MAX_DEPTH} levels"
            )
        raise YamlRefused([message]) from None
    except RecursionError:  # not expected within MAX_DEPTH; never a traceback
        raise YamlRefused(
            [f"1: <top>: nested too deeply to read; allowed: at most {MAX_DEPTH} levels"]
        ) from None
    finally:
        loader.dispose()
    return node, data


def line_map(
    node: yaml.Node, loc: tuple[str | int, ...], out: dict[tuple[str | int, ...], int]
) -> None:
    """Line of every YAML path (aliases included: their nodes are counted in the node
    budget, so this walk is bounded). Duplicate keys were refused while composing."""
    out.setdefault(loc, node.start_mark.line + 1)
    if isinstance(node, yaml.MappingNode):
        for key, value in node.value:
            sub = loc + (str(key.value),)
            out[sub] = key.start_mark.line + 1
            line_map(value, sub, out)
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            out[loc + (i,)] = item.start_mark.line + 1
            line_map(item, loc + (i,), out)
