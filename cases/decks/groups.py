"""The groups of input that modules 1 and 3 share: control words, solver settings, friction, materials, damping,
temperatures and subsurface points (the reference program's user guide, "Specification of the input file"). Each
reader takes the deck text, the case and its element's state, reads its group when the digits ask for it, checks
the values the reference program checks (DeckError naming the line and the field), and records them in the state.
"""
from __future__ import annotations

from rollcontact.cases.decks import digits as D
from rollcontact.cases.decks.case import Case, ElementState
from rollcontact.cases.decks.reader import DeckText, Item

FRICTION_NAMES = ("FSTAT", "FKIN", "FLIN1", "FLIN2", "FRAT1", "FRAT2", "FEXP1", "FEXP2", "SABSH1", "SABSH2", "FREF",
                  "TREF", "DFHEAT", "DTHEAT", "MEMDST", "MEM_S0", "NVF", "FRICTION_ROWS")
MATERIAL_NAMES = ("IF_METH", "VARIANT", "NINCLIN", "INCLIN", "CFNAME", "POISS1", "POISS2", "GG1", "GG2", "FLXZ",
                  "FG1", "FG2", "TC1", "TC2", "FLX", "K0_MF", "ALFAMF", "BETAMF", "GG3", "LAYTHK", "TAU_C0", "K_TAU")
#: the values of one friction law (after the optional ALPHA/SVF of a varied friction)
LAW_SPEC = {0: "FSTAT:d FKIN:d", 2: "FKIN:d FLIN1:d SABSH1:d FLIN2:d SABSH2:d",
            3: "FKIN:d FRAT1:d SABSH1:d FRAT2:d SABSH2:d", 4: "FKIN:d FEXP1:d SABSH1:d FEXP2:d SABSH2:d",
            6: "FREF:d TREF:d DFHEAT:d DTHEAT:d"}


def in_range(text: DeckText, item: Item, name: str, lo: float, hi: float, what: str = ""):
    """DeckError unless lo <= value <= hi (the reference program's own range checks)."""
    if not lo <= item.value <= hi:
        raise text.error(item.line, name, f"{item.value!r} is out of range: allowed {lo:g} <= {name} <= {hi:g}"
                                          f"{what}")


def read_control_words(text: DeckText, module: int, case: Case):
    """The three control words (and PSFLCIN when X = 1) into case.digits, checked against the allowed values."""
    words = D.WORDS[module]
    kinds = ("control word", "control word", "control word")
    specs = (f"{words[0]}:i", f"{words[1]}:i M2:I", f"{words[2]}:i")
    word_of = {}
    for word, spec, kind in zip(words, specs, kinds):
        got = text.read(f"{kind} {word}", spec)
        item = got[word]
        if item.value < 0:
            raise text.error(item.line, f"control word {word}", f"{item.value} is negative")
        for name, value in D.unpack(word, item.value).items():
            case.digits[name], case.digit_lines[name], word_of[name] = value, item.line, f"{word} = {item.value}"
        if "M2" in got:
            gap, m2 = divmod(got["M2"].value, 10)
            case.digits["M2"], case.digit_lines["M2"], word_of["M2"] = m2, got["M2"].line, f"M2 = {got['M2'].value}"
            case.digits["gap weighting"], case.digit_lines["gap weighting"] = gap, got["M2"].line
            if not 0 <= gap <= 2:
                raise text.error(got["M2"].line, "gap weighting (tens of M2)", f"{gap} is not allowed: 0-2")
    D.check(text.name, module, case.digits, case.digit_lines, word_of)
    if case.digits["X"] == 1:
        got = text.read("debug output PSFLCIN", "PSFLCIN:i R:I")
        case.read.update({"PSFLCIN": got["PSFLCIN"]})


def read_solver(text: DeckText, case: Case, state: ElementState):
    """Iteration constants and the G-digit's extra parameters; kept from the previous case when G = 1."""
    g = case.digits["G"]
    if g == 1:
        return
    got = text.read("iteration constants", "MAXGS:i MAXIN:i MAXNR:i MAXOUT:i EPS:d NPOT_MAX:I")
    if g in (2, 3):
        got.update(text.read("relaxation parameters", "OMEGAH:d OMEGAS:d INISLP:i OMGSLP:d"))
    elif g == 4:
        got.update(text.read("slip velocity iteration", "INISLP:i OMGSLP:d"))
    elif g == 5:
        got.update(text.read("parameters of GDsteady", "FDECAY:d BETATH:d KDOWFB:i D_IFC:d D_LIN:d D_CNS:d "
                                                       "D_SLP:d POW_S:d"))
    for name, hi in (("MAXGS", 9999), ("MAXIN", 999999), ("MAXNR", 9999), ("MAXOUT", 9999)):
        in_range(text, got[name], name, 1, hi)
    state.drop("MAXGS", "MAXIN", "MAXNR", "MAXOUT", "EPS", "NPOT_MAX", "OMEGAH", "OMEGAS", "INISLP", "OMGSLP",
               "FDECAY", "BETATH", "KDOWFB", "D_IFC", "D_LIN", "D_CNS", "D_SLP", "POW_S")
    state.keep(case, got)


def read_friction(text: DeckText, case: Case, state: ElementState, rows: int = 1):
    """The friction law's parameters (L = 0, 2, 3, 4, 6): one set, NVF sets with their ALPHA/SVF (V = 1, 2, module
    1) or one set per grid row (`rows`, V = 3, module 3), and the friction memory of the slip-velocity and
    temperature laws. L = 1 keeps the previous case's law."""
    law, vary = case.digits["L"], case.digits["V"]
    if law == 1:
        return
    if vary in (1, 2):
        nvf = text.read("number of friction points", "NVF:i")["NVF"]
        in_range(text, nvf, "NVF", 1, 100)
        rows = nvf.value
    param = {1: "ALPHA:a ", 2: "SVF:d "}.get(vary, "")
    sets = [text.read(f"friction law L={law}" + (f", set {k + 1}" if rows > 1 else ""), param + LAW_SPEC[law])
            for k in range(rows)]
    got = dict(sets[0]) if rows == 1 and not param else {}
    if rows > 1 or param:
        first = next(iter(sets[0].values())).line
        got["FRICTION_ROWS"] = Item([{k: it.value for k, it in s.items()} for s in sets], first)
        if vary in (1, 2):
            got["NVF"] = nvf
    if law in (2, 3, 4, 6):
        got.update(text.read("friction memory", "MEMDST:d MEM_S0:d"))
    for s in sets:
        if law == 0:
            in_range(text, s["FKIN"], "FKIN", 1e-4, 1e10)
            fs, fk = s["FSTAT"], s["FKIN"]
            if not 0.999 * fk.value <= fs.value <= 1.001 * fk.value:
                raise text.error(fs.line, "FSTAT", f"{fs.value!r} differs from FKIN = {fk.value!r}: the "
                                                   "reference program requires FSTAT = FKIN (L = 0)")
        elif law in (2, 3, 4):
            in_range(text, s["FKIN"], "FKIN", 0.0, 1e10)
            for name in ("FLIN1", "FLIN2", "FRAT1", "FRAT2", "FEXP1", "FEXP2"):
                if name in s:
                    in_range(text, s[name], name, 0.0, 1e20)
        elif law == 6:
            in_range(text, s["FREF"], "FREF", 0.0, 1e10)
    state.drop(*FRICTION_NAMES)
    state.keep(case, got)
    state.effective["L"] = law
    state.effective["V"] = vary


def read_materials(text: DeckText, module: int, case: Case, state: ElementState):
    """Elastic constants and the M-digit's material parameters, read when C = 2, 3, 4 (or 9, module 3)."""
    dg = case.digits
    got = {}
    if dg["C"] == 4 and module == 1:
        got.update(text.read("influence coefficient correction", "IF_METH:i VARIANT:i"))
    elif dg["C"] == 4:
        got.update(text.read("influence coefficient correction", "IF_METH:i VARIANT:i NINCLIN:i"))
        in_range(text, got["NINCLIN"], "NN", 1, 9999)
        got["INCLIN"] = text.read_array("conformal surface inclinations", "INCLIN", "a", 2 * got["NINCLIN"].value)
    if dg["C"] == 9:
        got.update(text.read("file of influence coefficients", "CFNAME:s"))
    got.update(text.read("material properties", "POISS1:d POISS2:d GG1:d GG2:d"))
    if dg["B"] == 1:
        got.update(text.read("compressible layer", "FLXZ:d"))
    mater = dg["M"]
    if mater == 1:
        got.update(text.read("viscoelastic material", "FG1:d FG2:d TC1:d TC2:d"))
    elif mater == 2:
        got.update(text.read("simplified theory", "FLX:d K0_MF:d ALFAMF:d BETAMF:d"))
    elif mater in (3, 5):
        got.update(text.read("slope reduction", "K0_MF:d ALFAMF:d BETAMF:d"))
    elif mater == 4:
        got.update(text.read("interfacial layer", "GG3:d LAYTHK:d TAU_C0:d K_TAU:d"))
    for name, lo, hi in (("POISS1", 0.0, 0.5), ("POISS2", 0.0, 0.5), ("GG1", 1e-5, 1e20), ("GG2", 1e-5, 1e20),
                         ("FLXZ", 1e-10, 1e20), ("FG1", 0.0, 1e20), ("FG2", 0.0, 1e20), ("TC1", 0.0, 1e20),
                         ("TC2", 0.0, 1e20), ("FLX", 1e-10, 1e20), ("GG3", 1e-5, 1e20)):
        if name in got:
            in_range(text, got[name], name, lo, hi)
    if mater in (2, 3, 5):
        for name, lo, hi in (("K0_MF", 1e-10, 1.0), ("ALFAMF", 0.0, 1.0), ("BETAMF", 0.0, 1e20)):
            in_range(text, got[name], name, lo, hi)
    state.drop(*MATERIAL_NAMES)
    state.keep(case, got)
    state.effective["C"] = dg["C"]
    state.effective["M"] = mater


def read_damping_and_heat(text: DeckText, case: Case, state: ElementState):
    """Damping parameters (M2 = 2; none with M2 = 0, kept with M2 = 1) and the temperature inputs (H = 3)."""
    dg = case.digits
    m2 = dg.get("M2", 1)
    if m2 == 0:
        state.drop("CDAMPN", "CDAMPT", "DFNMAX", "DFTMAX")
    if m2 == 2:
        got = text.read("damping parameters", "CDAMPN:d CDAMPT:d DFNMAX:d DFTMAX:d")
        for name, item in got.items():
            in_range(text, item, name, 0.0, 1e20)
        state.keep(case, got)
    if m2 != 1:
        state.effective["M2"] = m2
    if dg["H"] == 3:
        got = text.read("temperature inputs for body 1", "BKTEMP1:d HEATCP1:d LAMBDA1:d DENS1:d")
        got.update(text.read("temperature inputs for body 2", "BKTEMP2:d HEATCP2:d LAMBDA2:d DENS2:d"))
        for name, lo in (("HEATCP1", 1e-5), ("LAMBDA1", 1e-5), ("DENS1", 1e-12), ("HEATCP2", 1e-5),
                         ("LAMBDA2", 1e-5), ("DENS2", 1e-12)):
            in_range(text, got[name], name, lo, 1e20)
        if dg["M"] == 4:
            got.update(text.read("partitioning of plastic work", "BETAPL:d"))
            in_range(text, got["BETAPL"], "BETAPL", 0.0, 1.0)
        state.keep(case, got)


_ISUBS = (1, 2, 3, 5, 6, 7, 9)


def read_subsurface(text: DeckText, case: Case, state: ElementState):
    """The subsurface digits A_s, O_s (S = 2, 3) and blocks of points (S = 3), each block a dict with ISUBS, its
    selection and its z values (mm); ISUBS = 0 ends the list."""
    s = case.digits["S"]
    if s >= 2:
        got = text.read("A, O digits of the subsurface stresses", "MATFIL_S:i OUTPUT_S:i")
        state.subsurface_digits = (got["MATFIL_S"].value, got["OUTPUT_S"].value)
    if s == 3:
        blocks = []
        while True:
            item = text.read("subsurface block option", "ISUBS:i")["ISUBS"]
            isubs = item.value
            if isubs <= 0:
                break
            if isubs not in _ISUBS:
                raise text.error(item.line, "ISUBS", f"{isubs} is not allowed: 0 (end), 1, 2, 3, 5, 6, 7 or 9")
            block = {"ISUBS": isubs, "line": item.line}
            if isubs in (2, 6):
                cols = text.read("regular selection of grid columns", "IXL:i IXINC:i IXH:i")
                rows = text.read("regular selection of grid rows", "IYL:i IYINC:i IYH:i")
                for got in (cols, rows):
                    block.update({k: v.value for k, v in got.items()})
                for low, high in (("IXL", "IXH"), ("IYL", "IYH")):
                    got = cols if low == "IXL" else rows
                    in_range(text, got[low], low, 1, 999999)
                    in_range(text, got[high], high, got[low].value, 999999)
            elif isubs in (3, 7):
                got = text.read("irregular selection of elements", "NX:i NY:i")
                for name in ("NX", "NY"):
                    in_range(text, got[name], name, 1, 100000)
                block["IX"] = text.read_array("selected columns", "IX", "d", got["NX"].value).value
                block["IY"] = text.read_array("selected rows", "IY", "d", got["NY"].value).value
            if isubs in (1, 2, 3):
                got = text.read("regular spacing in z", "NZ:i ZL:d DZ:d")
                in_range(text, got["NZ"], "NZ", 1, 100000)
                in_range(text, got["DZ"], "DZ", 1e-9, 1e20)
                block["Z"] = [got["ZL"].value + k * got["DZ"].value for k in range(got["NZ"].value)]
            elif isubs in (5, 6, 7):
                nz = text.read("number of z values", "NZ:i")["NZ"]
                in_range(text, nz, "NZ", 1, 100000)
                block["Z"] = sorted(text.read_array("z values", "Z", "d", nz.value).value)
            elif isubs == 9:
                got = text.read("number of subsurface points in x, y, z", "NX:i NY:i NZ:i")
                for name in ("NX", "NY", "NZ"):
                    in_range(text, got[name], name, 1, 100000)
                for axis in "XYZ":
                    block[axis] = sorted(text.read_array(f"{axis.lower()} values", axis, "d",
                                                         got["N" + axis].value).value)
            blocks.append(block)
        state.subsurface = blocks
    if s in (1, 2) and not state.subsurface:
        raise text.error(case.digit_lines["S"], "control digit S (STRESS)",
                         f"{s} computes stresses at points stored by an earlier case, but none has given any "
                         "(S = 3 reads them)")
    case.subsurface = list(state.subsurface) if s >= 1 else []
    case.subsurface_digits = state.subsurface_digits if s >= 1 else None
