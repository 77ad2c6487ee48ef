"""`rollcontact import-contact`: a CONTACT input deck as scene files and a report (docs/contact_decks.md).

    rollcontact import-contact DECK.inp [-o DIR] [--overwrite]

Writes DIR/<deck>_case<N>.toml for every case (or history of cases) rollcontact can pose, the profile files they
name, DIR/<deck>_import.md (per case: converted or not, and every digit or value rollcontact cannot pose with what it
would need) and DIR/<deck>_import.json; prints the summary, one line per case or history, and the files. Default DIR: the deck's name in the current
folder. Exit codes: 0 imported (also when some cases do not convert: the report says why), 2 a deck that cannot be
read (the line and the field named) or a file that exists.
"""
from __future__ import annotations

from pathlib import Path


def register(subparsers):
    p = subparsers.add_parser(
        "import-contact", help="import a CONTACT input deck (.inp): scene files and a report of what converts",
        description="Read a deck of the reference program CONTACT (modules 1 and 3), write one scene per case (or "
                    "history of cases) rollcontact can pose, and report per case what it cannot pose and what it "
                    "would need. Units of the scenes: mm, N, MPa, degrees (rad for [wheelrail] angles).")
    p.add_argument("deck", help="the deck, <experim>.inp (or .inp.gz)")
    p.add_argument("-o", "--output", help="output folder (default: the deck's name, in the current folder)")
    p.add_argument("--overwrite", action="store_true", help="replace files that exist")
    p.set_defaults(func=import_handler)
    return p


def import_handler(args) -> int:
    from rollcontact.cases import api
    deck = Path(args.deck)
    out = Path(args.output) if args.output else Path(deck.name.removesuffix(".gz").removesuffix(".inp"))
    print(api.import_contact(deck, out, overwrite=args.overwrite).report())
    return 0
