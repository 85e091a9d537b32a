"""marble_maze: the agents' environments (marble_maze.agents), beside the messages and services
the workspace generates (marble_maze.msg, marble_maze.srv)."""
