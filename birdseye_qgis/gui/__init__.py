"""The desktop side of BirdsEye: the plugin object, its menu and toolbar, and dock widgets."""
