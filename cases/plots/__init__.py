"""Figures (PNG and PDF): of one run and of two runs side by side (`run_figures`), of a sweep folder
(`sweep_figures`), on the shared colours, normalisations and readers of `common`."""
