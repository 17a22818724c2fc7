# `fremond impact` refuses keys docs/problem-file.md does not list (never ignored) and missing required keys
# (never defaulted), at the top level, in the law and in its potentials.
source "$(dirname "$0")/impact_common.bash" "$1"

# Unknown keys.
refuse_edit "unknown top-level key (misspelt w_N)" "w_n" "unknown key of the impact-problem file" \
  newton_coulomb_point.json 'd["w_n"] = d.pop("w_N")'
refuse_edit "unknown top-level key (comment)" "comment" "unknown key" \
  fremond_point.json 'd["comment"] = "a note"'
refuse_edit "unknown key in a newton law (mu)" "law.mu" "unknown key of a 'newton' law" \
  newton_bar.json 'd["law"]["mu"] = 0.5'
refuse_edit "unknown key in a poisson law" "law.E" "unknown key of a 'poisson' law" \
  poisson_bar.json 'd["law"]["E"] = 0.5'
refuse_edit "unknown key in a newton_coulomb law" "law.friction" "unknown key" \
  newton_coulomb_point.json 'd["law"]["friction"] = 0.5'
refuse_edit "unknown key in a fremond law (e)" "law.e" "unknown key of a 'fremond' law" \
  fremond_point.json 'd["law"]["e"] = 0.5'
refuse_edit "unknown key in a normal potential" "law.normal.q" \
  "not a parameter of potential 'power'" fremond_point.json 'd["law"]["normal"]["q"] = 2'
refuse_edit "unknown key in a tangential potential" "law.tangential.p" \
  "not a parameter of potential 'deadzone_power'" \
  fremond_viscous_point.json 'd["law"]["tangential"]["p"] = 2'
refuse_edit "unknown key in the tangential coulomb law" "law.tangential.k" \
  "unknown key of the tangential law 'coulomb'" \
  fremond_coulomb_point.json 'd["law"]["tangential"]["k"] = 2'

# Missing required keys.
for key in M W_N qdot_A law; do
  refuse_edit "missing $key" "$key" "missing (required)" fremond_point.json "del d['$key']"
done
refuse_edit "missing law.type" "law.type" "missing (required)" newton_bar.json 'del d["law"]["type"]'
refuse_edit "missing law.e (newton)" "law.e" "missing (required)" newton_bar.json \
  'del d["law"]["e"]'
refuse_edit "missing law.e (poisson_coulomb)" "law.e" "missing (required)" \
  poisson_coulomb_point.json 'del d["law"]["e"]'
refuse_edit "missing law.mu (newton_coulomb)" "law.mu" "missing (required)" \
  newton_coulomb_point.json 'del d["law"]["mu"]'
refuse_edit "missing law.normal (fremond)" "law.normal" "missing (required)" \
  fremond_point.json 'del d["law"]["normal"]'
refuse_edit "missing law.normal.potential" "law.normal.potential" "missing (required)" \
  fremond_point.json 'del d["law"]["normal"]["potential"]'
refuse_edit "missing parameter p of power" "law.normal.p" "missing, required by potential 'power'" \
  fremond_point.json 'del d["law"]["normal"]["p"]'
refuse_edit "missing parameter q of deadzone_power" "law.tangential.q" \
  "missing, required by potential 'deadzone_power'" \
  fremond_viscous_point.json 'del d["law"]["tangential"]["q"]'
refuse_edit "missing law.tangential.potential" "law.tangential.potential" "missing (required)" \
  fremond_viscous_point.json 'del d["law"]["tangential"]["potential"]'
refuse_edit "missing law.tangential.mu (coulomb)" "law.tangential.mu" "missing (required)" \
  fremond_coulomb_point.json 'del d["law"]["tangential"]["mu"]'

# Keys of the wrong kind.
refuse_edit "law not an object" "law" "must be a JSON object, got a string" \
  newton_bar.json 'd["law"] = "newton"'
refuse_edit "law.type not a string" "law.type" "must be a string, got the number 1" \
  newton_bar.json 'd["law"]["type"] = 1'
refuse_edit "law.normal not an object" "law.normal" "must be a JSON object" \
  fremond_point.json 'd["law"]["normal"] = "power"'
refuse_edit "law.tangential null" "law.tangential" "must be a JSON object, got null" \
  fremond_point.json 'd["law"]["tangential"] = None'
refuse_edit "law.normal.potential not a string" "law.normal.potential" "must be a string" \
  fremond_point.json 'd["law"]["normal"]["potential"] = ["power"]'

finish
