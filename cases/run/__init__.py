"""One run of a scene: the scene discretised onto a grid and a load path, stepped by the BEM solver (`bem_run`) or
the 1-D MDR model (`mdr_run`), and continued from a stored step (`restart`). Units: mm, N, MPa."""
