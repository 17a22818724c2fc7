# `fremond impact` with the classical laws of docs/laws.md (newton, poisson, newton_coulomb,
# poisson_coulomb), on problems whose answer is known by hand.
source "$(dirname "$0")/impact_common.bash" "$1"

# Shared Python: the problem's data as plain lists, and its velocities and energy.
SETUP='
M, WN = p["M"], p["W_N"]
n, c = len(M), len(WN[0])
WT = p.get("W_T")
qA = p["qdot_A"]
col = lambda W, i: [W[k][i] for k in range(n)]
dot = lambda a, b: sum(x * y for x, y in zip(a, b))
Minv = lambda v: [v[k] / M[k][k] for k in range(n)]  # the mass matrices here are diagonal
energy = lambda q: 0.5 * sum(q[i] * M[i][j] * q[j] for i in range(n) for j in range(n))
'

# Newton, one frictionless contact: the closed form of eq. (6) on the bar of the paper's Fig. 1,
# P_N = −(1 + e) D_NA / G_NN, D_NE = −e D_NA; W_T is given but the law has no friction: P_T = 0.
NEWTON_BAR="$SETUP"'
e = p["law"]["e"]
w = col(WN, 0)
DNA = dot(w, qA)
GNN = dot(w, Minv(w))
PN = -(1 + e) * DNA / GNN
qE = [a + b * PN for a, b in zip(qA, Minv(w))]
near(d["D_NA"], [DNA])
near(d["P_N"], [PN])
near(d["P_T"], [0.0])
near(d["D_NE"], [-e * DNA])
near(d["qdot_E"], qE)
near(d["D_TA"], [dot(col(WT, 0), qA)])
near(d["D_TE"], [dot(col(WT, 0), qE)])
near(d["energy_change"], energy(qE) - energy(qA), 1e-12, 1e-12)
assert d["admissibility"]["admissible"] and d["unique"]
assert d["solver"]["status"] == "converged"
'
run_impact "$DATA/newton_bar.json"
expect_status "newton, bar" 0
check_json "newton, bar: eq. (6)" "$NEWTON_BAR" newton_bar.json

# Poisson, one frictionless contact: the same outcome as Newton, with its compression phase
# P_NC = −D_NA / G_NN, D_NC = 0 and P_N = (1 + e) P_NC.
run_impact "$DATA/poisson_bar.json"
expect_status "poisson, bar" 0
check_json "poisson, bar: as newton" "$NEWTON_BAR" poisson_bar.json
check_json "poisson, bar: compression phase" "$SETUP"'
w = col(WN, 0)
PNC = -dot(w, qA) / dot(w, Minv(w))
near(d["P_NC"], [PNC])
near(d["D_NC"], [0.0])
near(d["P_N"], [(1 + p["law"]["e"]) * PNC])
' poisson_bar.json

# One point mass sliding on the ground (G diagonal: the normal and tangential problems decouple):
# D_NA = −1, e = 0.5: P_N = 1.5; D_TA = 2, mu = 0.1: it keeps sliding, P_T = −0.15, D_TE = 1.85.
POINT='
near(d["P_N"], [1.5])
near(d["P_T"], [-0.15])
near(d["D_NE"], [0.5])
near(d["D_TE"], [1.85])
near(d["qdot_E"], [1.85, 0.5])
near(d["energy_change"], 0.5 * (1.85**2 + 0.5**2) - 0.5 * (2**2 + 1**2))
assert d["unique"] and d["admissibility"]["admissible"]
assert d["solver"]["status"] == "converged"
'
run_impact "$DATA/newton_coulomb_point.json"
expect_status "newton_coulomb, point mass" 0
check_json "newton_coulomb, point mass: sliding" "$POINT"
run_impact "$DATA/poisson_coulomb_point.json"
expect_status "poisson_coulomb, point mass" 0
check_json "poisson_coulomb, point mass: sliding" "$POINT"
# Per phase (Pfeiffer & Glocker): compression P_NC = 1, P_TC = −0.1, D_TC = 1.9.
check_json "poisson_coulomb, point mass: phases" '
near(d["P_NC"], [1.0])
near(d["P_TC"], [-0.1])
near(d["D_NC"], [0.0])
near(d["D_TC"], [1.9])
'

# Two independent contacts with per-contact e and mu (lists in the file): contact 1 has
# D_NA = −2, e = 0.25, D_TA = 1, mu = 0.2: P_NC = 2, P_N = 2.5, P_T = −0.5, D_TE = 0.5.
run_impact "$DATA/poisson_coulomb_two_contacts.json"
expect_status "poisson_coulomb, two contacts" 0
check_json "poisson_coulomb, two contacts: per-contact e and mu" '
near(d["P_N"], [1.5, 2.5])
near(d["P_T"], [-0.15, -0.5])
near(d["D_NE"], [0.5, 0.5])
near(d["D_TE"], [1.85, 0.5])
near(d["P_NC"], [1.0, 2.0])
near(d["P_TC"], [-0.1, -0.4])
'

# The example of docs/problem-file.md: Newton + Coulomb at the bar's lower end, mu = 1 below the Painlevé bound
# (mu|G_NT| < G_NN). Sliding either way contradicts its own sign; the contact sticks: D_TE = 0,
# D_NE = −e D_NA, i.e. G P = (−(1 + e) D_NA, −D_TA), with |P_T| ≤ mu P_N.
run_impact "$DATA/spec_example.json"
expect_status "spec example" 0
check_json "spec example: sticking" "$SETUP"'
wn, wt = col(WN, 0), col(WT, 0)
DNA, DTA = dot(wn, qA), dot(wt, qA)
a, b, g = dot(wn, Minv(wn)), dot(wn, Minv(wt)), dot(wt, Minv(wt))
r1, r2 = -(1 + 0.9) * DNA, -DTA
det = a * g - b * b
PN, PT = (g * r1 - b * r2) / det, (a * r2 - b * r1) / det
assert abs(PT) <= 1.0 * PN
near(d["P_N"], [PN], 1e-12)
near(d["P_T"], [PT], 1e-12)
near(d["D_NE"], [-0.9 * DNA], 1e-12)
near(d["D_TE"], [0.0], 0, 1e-12)
assert d["unique"]
' spec_example.json

finish
