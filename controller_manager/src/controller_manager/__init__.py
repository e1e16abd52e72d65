"""controller_manager stand-in: the spawner, the controller_manager command line and
controller_manager_interface, talking to <ns>/controller_manager/* (served by tianracer_sim)."""
