"""CONTACT input decks (`<experim>.inp`, modules 1 and 3): read them case by case, convert what rollcontact can pose
into scene TOML files, and report what it cannot (docs/contact_decks.md)."""
