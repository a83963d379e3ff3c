"""Contact of a rigid indenter with the FEM body: the constraints written once
(:mod:`.constraints`: the stick/slip active set, the load ladder, the contact's edge), against
a linear body (:mod:`.linear`: one factorization, the surface compliance on the contact nodes;
frictionless, :mod:`.stick` bonded or Coulomb, :mod:`.rate` a Prony body pressed at a rate)
or a finite-strain body (:mod:`.finite`: Newton, frictionless; :mod:`.finite_stick` bonded or
Coulomb)."""
