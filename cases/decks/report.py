"""The import report of a deck (markdown): a table of its problems, then per problem the cases it covers, whether
they convert and into which scene, every control digit or value rollcontact cannot pose (name, value, line, what it
would need), the differences of discretisation, and the reference program's settings that do not change the
problem (ignored)."""
from __future__ import annotations


def _cases(numbers: list[int]) -> str:
    return f"case {numbers[0]}" if len(numbers) == 1 else f"cases {numbers[0]}-{numbers[-1]}"


def report_text(result) -> str:
    """The report of a DeckImport (cases.decks.importer)."""
    from rollcontact.cases.decks.importer import kind_text, steps_text
    deck = result.deck
    lines = [f"# CONTACT deck `{deck.name}.inp`: import report", "", result.summary() + f" (converted: "
             f"{result.status}).", ""]
    for note in deck.notes:
        lines.append(f"Note: {note}.")
    lines += ["| cases | problem | status | scene |", "|---|---|---|---|"]
    for p in result.problems:
        if p.kind == "skipped":
            status, scene = "skipped", ""
        elif p.converted:
            status, scene = "converted", f"`{p.name}.toml`"
        else:
            status, scene = "not converted", ""
        lines.append(f"| {_cases(p.numbers)} | {kind_text(p.kind)} | {status} | {scene} |")
    for p in result.problems:
        lines += ["", f"## {_cases(p.numbers).capitalize()}: {kind_text(p.kind)}", ""]
        if p.kind == "skipped":
            lines.append(f"Skipped: {p.reason}.")
            continue
        d = p.draft
        if p.converted:
            lines.append(f"Converted: `{p.name}.toml`" + (f" (one run; {steps_text(p.steps)})" if len(p.steps) > 1
                                                          else "") + ".")
            if d.run_options.get("stresses"):
                lines.append("Subsurface stresses: `rollcontact run ... --stresses --depths " +
                             ",".join(f"{z:g}" for z in d.run_options["depths"]) + "`.")
        else:
            lines.append("Not converted; rollcontact cannot pose:")
            lines += [f"- {u.text()}" for u in d.unsupported]
        for case in p.cases:
            lines += [f"- case {case.number}: {n}" for n in case.notes]
        if d.notes:
            lines.append("Differences:" if p.converted else "Also:")
            lines += [f"- {n}" for n in d.notes]
        if d.ignored:
            lines.append("Ignored (they do not change the problem):")
            lines += [f"- {n}" for n in d.ignored]
    return "\n".join(lines) + "\n"
