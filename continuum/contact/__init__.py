"""The rigid footing's contact with the soil: its kinematics and the contact solver
(:mod:`.footing`), and the contact in one explicit step (:mod:`.step`)."""
