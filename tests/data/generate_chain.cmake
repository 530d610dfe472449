# ctest helper: write a scene of an N-link chain pivoted end to end (-DN=20000 -DOUT=file.yaml),
# for `mo2d info` (dense, its matrices would need tens of GB; sparse since issue 14: refused only
# under a tighter --max-memory).
set(text "name: chain${N}\nground: {O: [0, 0]}\nbodies:\n")
set(joints "joints:\n")
math(EXPR last "${N} - 1")
foreach(k RANGE 0 ${last})
  math(EXPR k1 "${k} + 1")
  string(APPEND text "  l${k}: {nodes: {A: [${k}, 0], B: [${k1}, 0]}, mass: 1, inertia: 0.1}\n")
  if(k EQUAL 0)
    string(APPEND joints "  j0: {type: revolute, node_a: ground.O, node_b: l0.A}\n")
  else()
    math(EXPR km "${k} - 1")
    string(APPEND joints "  j${k}: {type: revolute, node_a: l${km}.B, node_b: l${k}.A}\n")
  endif()
endforeach()
file(WRITE "${OUT}" "${text}${joints}loads: {gravity: [0, -9.81]}\n")
