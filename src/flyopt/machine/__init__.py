"""The machine: torque curves, expressions, mechanisms, motors and transmissions, reduced to one shaft."""
